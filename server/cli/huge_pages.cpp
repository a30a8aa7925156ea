#include "cli/huge_pages.h"

#include <unistd.h>

#include <climits>
#include <cstdlib>

namespace glint {

void request_huge_pages(char** argv) {
    if (std::getenv("GLIBC_TUNABLES") != nullptr) return;
    // The executable's own path rather than /proc/self/exe itself, which a tool running glint
    // (valgrind) may resolve to its own binary.
    char path[PATH_MAX];
    const ssize_t length = readlink("/proc/self/exe", path, sizeof path - 1);
    if (length <= 0) return;
    path[length] = '\0';
    if (setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 1) != 0) return;
    execv(path, argv);
    unsetenv("GLIBC_TUNABLES");  // exec failed: run on as started
}

}  // namespace glint
