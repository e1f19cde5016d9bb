// SPDX-License-Identifier: MIT
// A full disk, simulated by a file-size limit (ulimit -f) in a child shell
// that ignores SIGXFSZ, so writes fail with EFBIG as on a full disk: the
// error names the file, and nothing is left that looks like a finished run
// or a valid checkpoint.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <functional>
#include <string>

#include <fmt/format.h>

#include "io/checkpoint.hpp"
#include "io/vtk_output.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;

class FullDisk : public tumble::test_support::ScratchTest {
protected:
    // Runs tumble with files limited to `kib` KiB.
    tumble::test_support::CommandResult limited(int kib, const std::string& arguments) {
        return tumble::test_support::run_command("bash -c \"trap '' XFSZ; ulimit -f " + std::to_string(kib) +
                                                 "; exec " + TUMBLE_BINARY + " " + arguments + "\"");
    }
    // Runs tumble with files limited to `kib` KiB and SIGXFSZ at its default
    // disposition (the process ends), as a shell's `ulimit -f` leaves it.
    // exit_code is -SIGNAL if a signal ended it.
    tumble::test_support::CommandResult limited_with_default_signal(int kib, const std::string& arguments) {
        const fs::path log = dir_ / "limited.log";
        const std::string command =
            std::string("exec ") + TUMBLE_BINARY + " " + arguments + " > " + log.string() + " 2>&1";
        const pid_t pid = fork();
        if (pid == 0) {
            std::signal(SIGXFSZ, SIG_DFL);
            const rlim_t bytes = static_cast<rlim_t>(kib) * 1024;
            const rlimit limit{bytes, bytes};
            if (setrlimit(RLIMIT_FSIZE, &limit) != 0) _exit(126);
            execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
            _exit(127);
        }
        int status = 0;
        waitpid(pid, &status, 0);
        return {WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status), tumble::test_support::read_file(log)};
    }
    // Runs `write` in a child process whose files are limited to `bytes`,
    // SIGXFSZ ignored (a write past the limit fails with EFBIG): the message
    // of the error it threw, or "" if none.
    static std::string error_under_file_limit(std::size_t bytes, const std::function<void()>& write) {
        int pipe_fds[2];
        if (pipe(pipe_fds) != 0) return "pipe failed";
        const pid_t pid = fork();
        if (pid == 0) {
            close(pipe_fds[0]);
            std::signal(SIGXFSZ, SIG_IGN);
            const rlimit limit{bytes, bytes};
            std::string message = setrlimit(RLIMIT_FSIZE, &limit) == 0 ? "" : "setrlimit failed";
            try {
                write();
            } catch (const std::exception& e) {
                message = e.what();
            }
            if (::write(pipe_fds[1], message.data(), message.size()) < 0) _exit(1);
            _exit(0);
        }
        close(pipe_fds[1]);
        std::string message;
        char buffer[4096];
        for (ssize_t n; (n = read(pipe_fds[0], buffer, sizeof buffer)) > 0;)
            message.append(buffer, static_cast<std::size_t>(n));
        close(pipe_fds[0]);
        waitpid(pid, nullptr, 0);
        return message;
    }
    // No temporary files, no summary, and every checkpoint loads.
    void expect_nothing_looks_valid(const fs::path& run) {
        for (const auto& entry : fs::recursive_directory_iterator(run))
            EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();
        EXPECT_FALSE(fs::exists(run / "summary.json"));
        EXPECT_FALSE(fs::exists(run / "run.json"));
        for (const fs::path& file : tumble::io::checkpoint_files(run))
            EXPECT_NO_THROW(tumble::io::decode_checkpoint(tumble::test_support::read_file(file), file.string()));
    }
};

TEST_F(FullDisk, ACheckpointThatDoesNotFitIsReportedAndRemoved) {
    // The checkpoints of this drum are about 70 KiB; the other files stay under 40.
    const fs::path run = dir_ / "drum";
    const auto r = limited(40, "drum -q --mode self --grains 20 --length 0.03 --diameter 0.03 --omega 10 "
                               "--revolutions 0.2 --no-plot --checkpoint-every-revolutions 0.05 --out " +
                                   run.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find((run / "checkpoints" / "000001.tck.tmp").string() + ": writing (disk full?) failed"),
              std::string::npos)
        << r.output;
    EXPECT_TRUE(tumble::io::checkpoint_files(run).empty());
    expect_nothing_looks_valid(run);
}

TEST_F(FullDisk, AnOutputFileThatDoesNotFitIsReported) {
    // 2 samples per step in a 16 KiB limit: time_series.csv fills up first.
    const fs::path scenario = write("box.toml", tumble::test_support::walled_box_scenario("0.05", "", R"([output]
time_series_interval = 1e-9
)"));
    const fs::path run = dir_ / "box";
    const auto r = limited(16, "run -q " + scenario.string() + " --out " + run.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find((run / "time_series.csv").string() + ": write failed (disk full"), std::string::npos)
        << r.output;
    expect_nothing_looks_valid(run);
}

TEST_F(FullDisk, AFileSizeLimitIsReportedNotASignalAndLeavesNoCutFile) {
    // The demo's first snapshot is about 100 KiB; the files before it fit in 40.
    const fs::path run = dir_ / "demo";
    const auto r = limited_with_default_signal(
        40, "run -q " + std::string(TUMBLE_SOURCE_DIR) + "/examples/demo.toml --out " + run.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    const fs::path snapshot = run / "snapshots" / "000000.csv";
    EXPECT_NE(r.output.find(snapshot.string() + ".tmp: writing (disk full?) failed: File too large"), std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(snapshot)) << "a cut snapshot under its final name";
    expect_nothing_looks_valid(run);
}

TEST_F(FullDisk, AnIndexThatNoLongerFitsKeepsTheLastWholeOneAndNoTemporaryFile) {
    const fs::path pvd = dir_ / "particles.pvd";
    const std::string error = error_under_file_limit(2048, [&] {
        tumble::io::PvdIndex index(pvd);
        for (int k = 0; k < 100; ++k) index.add(0.01 * k, fs::path("snapshots") / fmt::format("{:06d}.vtu", k));
    });
    EXPECT_NE(error.find(pvd.string() + ".tmp: writing (disk full?) failed: File too large"), std::string::npos)
        << error;
    EXPECT_FALSE(fs::exists(dir_ / "particles.pvd.tmp"));
    const std::string index = tumble::test_support::read_file(pvd);
    EXPECT_NE(index.find("000010.vtu"), std::string::npos) << index;
    EXPECT_TRUE(index.ends_with("</VTKFile>\n")) << index;
}

TEST_F(FullDisk, AnUnwritableDirectoryIsReportedWithThePath) {
    const fs::path blocked = write("file", "not a directory");
    const auto r = tumble::test_support::run_command(std::string(TUMBLE_BINARY) +
                                                     " drum -q --grains 20 --revolutions 0.1 --out " +
                                                     (blocked / "run").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find((blocked / "run").string() + ": cannot create the output directory"), std::string::npos)
        << r.output;
}

}  // namespace
