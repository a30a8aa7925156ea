#include "service/job_film.h"

namespace glint {

Partial partial_of(const RenderJob& render, uint64_t fingerprint, uint32_t spp_done) {
    Partial p;
    p.fingerprint = fingerprint;
    p.first_sample = render.settings().first_sample;
    p.end_sample = render.settings().first_sample + spp_done;
    p.encoding = render.settings().encoding;
    p.film = render.film();
    return p;
}

}  // namespace glint
