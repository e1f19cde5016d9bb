// SPDX-License-Identifier: MIT
// One process per run directory. Every command that writes a run directory
// (run, drum, resume, analyze, sweep) first takes an exclusive lock (flock)
// on DIR/.tumble.lock and holds it until it exits; the kernel releases it
// when the process ends, however it ends (kill -9 included), so a lock is
// never left behind. A second process is refused, naming the holder's pid.
// The lock file is also the first file tumble writes into a directory: its
// presence marks a directory whose run files tumble may remove (--force).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace tumble::io {

inline constexpr const char* run_lock_file = ".tumble.lock";

class RunLock {
public:
    // Locks `directory` or throws tumble::Error: "DIR: no such run
    // directory", "DIR: in use by another tumble process (pid N) ...".
    explicit RunLock(const std::filesystem::path& directory);
    // Locks `directory` if no other process holds it; nullopt if one does
    // (a run going on). Throws as the constructor for anything else.
    static std::optional<RunLock> if_free(const std::filesystem::path& directory);
    RunLock(RunLock&& other) noexcept;
    RunLock& operator=(RunLock&& other) noexcept;
    RunLock(const RunLock&) = delete;
    RunLock& operator=(const RunLock&) = delete;
    ~RunLock();

private:
    RunLock() = default;
    // Takes the lock; if another process holds it, returns its pid (as the
    // lock file says) and holds nothing.
    std::optional<std::string> acquire(const std::filesystem::path& directory);
    int fd_ = -1;
};

}  // namespace tumble::io
