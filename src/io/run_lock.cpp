// SPDX-License-Identifier: MIT
#include "io/run_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <utility>

#include "tumble/core/error.hpp"

namespace tumble::io {

RunLock::RunLock(const std::filesystem::path& directory) {
    if (const std::optional<std::string> holder = acquire(directory))
        throw Error(directory.string() + ": in use by another tumble process (pid " + *holder + ", holding " +
                    (directory / run_lock_file).string() + "); wait for it to end, or stop it first");
}

std::optional<RunLock> RunLock::if_free(const std::filesystem::path& directory) {
    RunLock lock;
    if (lock.acquire(directory)) return std::nullopt;
    return lock;
}

std::optional<std::string> RunLock::acquire(const std::filesystem::path& directory) {
    if (!std::filesystem::is_directory(directory)) throw Error(directory.string() + ": no such run directory");
    const std::filesystem::path file = directory / run_lock_file;
    // O_CLOEXEC: the sweep's child processes do not inherit the sweep's lock.
    fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw Error(file.string() + ": cannot open the lock file: " + std::strerror(errno));
    const bool locked = ::flock(fd_, LOCK_EX | LOCK_NB) == 0;
    if (!locked) {
        const int why = errno;
        char pid[32] = {};
        [[maybe_unused]] const ssize_t n = ::pread(fd_, pid, sizeof pid - 1, 0);
        ::close(fd_);
        fd_ = -1;
        if (why != EWOULDBLOCK) throw Error(file.string() + ": cannot lock: " + std::strerror(why));
        std::string holder(pid);
        while (!holder.empty() && (holder.back() == '\n' || holder.back() == ' ')) holder.pop_back();
        return holder.empty() ? std::string("unknown") : holder;
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
        const int why = errno;
        ::close(fd_);
        fd_ = -1;
        throw Error(file.string() + ": cannot write the lock file: " + std::strerror(why));
    }
    return std::nullopt;
}

RunLock::RunLock(RunLock&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}

RunLock& RunLock::operator=(RunLock&& other) noexcept {
    std::swap(fd_, other.fd_);
    return *this;
}

RunLock::~RunLock() {
    if (fd_ >= 0) ::close(fd_);  // releases the lock
}

}  // namespace tumble::io
