// Makes a job's frames from its film and publishes them to its status: the PNG, the EXR's
// layers, the denoiser's half buffers and an adaptive job's samples picture, each made once a
// frame, outside the status's lock, so watchers only ever wait for the pointers to change.
#pragma once

#include "render/renderer.h"
#include "service/job_status.h"

namespace glint {

class FramePublisher {
public:
    // Publishes `render`'s film into `status`; both outlive the publisher.
    FramePublisher(const RenderJob& render, JobStatus& status) : render_(render), status_(status) {}

    // The film as it is now, in `state` at `progress`. Only the render's thread publishes.
    void publish(JobState state, const Progress& progress) const;
    // `preview` (the first, throwaway picture) as a running job's frame; the film is untouched.
    void publish_preview(const Image& preview) const;
    // A restored job as it ended: the pictures of its final `film` (none without one).
    void publish_restored(const Film* film, JobState state, const Progress& progress) const;

private:
    const RenderJob& render_;
    JobStatus& status_;
};

}  // namespace glint
