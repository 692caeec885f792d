// Another program keeping one core busy: a child process that spins until it is stopped. On a
// shared machine the physics' threads meet such programs, and a pool that waited for a thread the
// system had not scheduled lost a whole time slice a batch; the bench's "busy machine" section
// times the scenes while one of these runs.
#pragma once

#include <sys/types.h>

namespace softbody::app {

class BusyCore {
public:
    // Starts the spinning child (std::runtime_error where a process cannot start one: the browser).
    BusyCore();
    // Stops it and waits for it.
    ~BusyCore();
    BusyCore(const BusyCore&) = delete;
    BusyCore& operator=(const BusyCore&) = delete;

    pid_t pid() const { return pid_; }

private:
    pid_t pid_ = -1;
};

}  // namespace softbody::app
