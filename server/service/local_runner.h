// A job rendered on this server's render threads, pass by pass: each pass published and, with a
// store, checkpointed; a suspend stops it at the next pass boundary.
#pragma once

#include "service/job_runner.h"

namespace glint {

class LocalRunner : public JobRunner {
public:
    explicit LocalRunner(JobContext job) : job_(job) {}

    void run(ThreadPool& pool) override;
    void cancel_before_start() override {}
    bool on_farm() const override { return false; }

private:
    Progress with_earlier_time(Progress p) const;
    void after_pass(const Progress& pass);

    JobContext job_;
};

}  // namespace glint
