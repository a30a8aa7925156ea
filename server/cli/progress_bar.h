// Progress of a render on the terminal: a bar with ETA redrawn in place on a TTY, plain
// progress lines otherwise (logs, CI).
#pragma once

#include <cstdio>

#include "render/renderer.h"

namespace glint {

class ProgressBar {
public:
    explicit ProgressBar(std::FILE* out);
    void update(const Progress& p);
    void finish();  // ends the bar's line

private:
    std::FILE* out_;
    bool interactive_;
    bool drawn_ = false;
};

}  // namespace glint
