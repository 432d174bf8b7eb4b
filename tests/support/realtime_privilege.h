#pragma once
// Real-time scheduling with and without the privilege it needs, for the tests of `run --realtime`:
// a forked child drops CAP_SYS_NICE and sets its RLIMIT_RTPRIO, so that the refusal is tested even
// where the test runs as root.
#include <linux/capability.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <functional>

namespace hybridlab::test {

// The child's exit status where it could not drop the privilege or set the limit (raising a hard
// limit needs CAP_SYS_RESOURCE, which containers often lack).
constexpr int kChildCannotDrop = 77;

// Runs `body` in a forked child without CAP_SYS_NICE and with RLIMIT_RTPRIO `rtprio` (the highest
// real-time priority it may then take); returns the child's exit status (-1: it did not exit).
inline int inChildWithoutRealTimePrivilege(rlim_t rtprio, const std::function<int()>& body) {
    const pid_t child = fork();
    if (child == 0) {
        __user_cap_header_struct header{_LINUX_CAPABILITY_VERSION_3, 0};
        __user_cap_data_struct caps[2]{};
        if (syscall(SYS_capget, &header, caps) != 0) _exit(kChildCannotDrop);
        const unsigned bit = 1u << (CAP_SYS_NICE % 32);
        caps[CAP_SYS_NICE / 32].effective &= ~bit;
        caps[CAP_SYS_NICE / 32].permitted &= ~bit;
        caps[CAP_SYS_NICE / 32].inheritable &= ~bit;
        const rlimit limit{rtprio, rtprio};
        if (setrlimit(RLIMIT_RTPRIO, &limit) != 0 || syscall(SYS_capset, &header, caps) != 0) _exit(kChildCannotDrop);
        _exit(body());
    }
    int status = 0;
    if (child < 0 || waitpid(child, &status, 0) != child || !WIFEXITED(status)) return -1;
    return WEXITSTATUS(status);
}

}  // namespace hybridlab::test
