#include "app/batch.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <iostream>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

extern char** environ;

namespace velvet::cli {

int parseBatchSettings(const Arguments& args, const char* command, BatchSettings& out) {
    out.jobs = int(std::max(1u, std::thread::hardware_concurrency()));
    out.asked = args.has("jobs") || args.has("shard");
    if (args.has("jobs")) {
        const std::string text = args.value("jobs");
        int n = 0;
        auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
        if (ec != std::errc() || ptr != text.data() + text.size() || n < 1 || n > 256) {
            std::cerr << "velvet " << command << ": --jobs expects 1 to 256, got '" << text
                      << "'\nRun 'velvet " << command << " --help' for usage.\n";
            return UsageError;
        }
        out.jobs = n;
    }
    if (args.has("shard")) {
        const auto shard = parseShard(args.value("shard"));
        if (!shard) {
            std::cerr << "velvet " << command << ": --shard expects K/N with 0 <= K < N, got '"
                      << args.value("shard") << "'\nRun 'velvet " << command
                      << " --help' for usage.\n";
            return UsageError;
        }
        out.shard = *shard;
    }
    return Ok;
}

std::vector<std::string> forwardOptions(const Arguments& args, const std::vector<OptionSpec>& specs,
                                        const std::vector<std::string_view>& skip) {
    std::vector<std::string> words;
    for (const auto& [name, value] : args.options) {
        if (std::find(skip.begin(), skip.end(), name) != skip.end())
            continue;
        const auto spec = std::find_if(specs.begin(), specs.end(),
                                       [&](const OptionSpec& s) { return s.longName == name; });
        words.push_back("--" + name + (spec != specs.end() && spec->takesValue ? "=" + value : ""));
    }
    return words;
}

namespace {

using Clock = std::chrono::steady_clock;

struct Running {
    const BatchJob* job = nullptr;
    pid_t pid = -1;
    int out = -1, err = -1; ///< read ends of the child's stdout and stderr
    std::string stdoutText, stderrText;
};

/// This executable, for the children (the path the kernel ran, not argv[0]).
std::string selfPath() {
    std::error_code ec;
    const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
    return ec ? std::string("velvet") : self.string();
}

bool spawn(const std::string& exe, const BatchJob& job, Running& r, std::string* error) {
    int outPipe[2], errPipe[2];
    if (pipe2(outPipe, O_CLOEXEC) != 0)
        return *error = std::strerror(errno), false;
    if (pipe2(errPipe, O_CLOEXEC) != 0) {
        close(outPipe[0]), close(outPipe[1]);
        return *error = std::strerror(errno), false;
    }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, outPipe[1], STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&actions, errPipe[1], STDERR_FILENO);
    std::vector<char*> argv;
    std::string arg0 = exe;
    argv.push_back(arg0.data());
    std::vector<std::string> args = job.args;
    for (std::string& a : args)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    const int rc = posix_spawn(&r.pid, exe.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    close(outPipe[1]);
    close(errPipe[1]);
    if (rc != 0) {
        close(outPipe[0]), close(errPipe[0]);
        *error = std::strerror(rc);
        return false;
    }
    r.job = &job;
    r.out = outPipe[0];
    r.err = errPipe[0];
    return true;
}

/// Reads what is there from @p fd into @p text; closes it (-1) at end of file.
void drain(int& fd, std::string& text) {
    char buffer[8192];
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n > 0) {
        text.append(buffer, size_t(n));
    } else if (n == 0 || (errno != EINTR && errno != EAGAIN)) {
        close(fd);
        fd = -1;
    }
}

/// The last non-empty line of @p text.
std::string lastLine(const std::string& text) {
    size_t end = text.find_last_not_of("\n\r ");
    if (end == std::string::npos)
        return {};
    const size_t begin = text.rfind('\n', end);
    return text.substr(begin == std::string::npos ? 0 : begin + 1,
                       end + 1 - (begin == std::string::npos ? 0 : begin + 1));
}

} // namespace

int runBatch(const std::vector<BatchJob>& jobs, int parallel, const char* command) {
    const std::string exe = selfPath();
    const std::string prefix = std::string("velvet ") + command + ": ";
    const int total = int(jobs.size());
    const auto start = Clock::now();
    std::vector<Running> running;
    std::vector<std::string> failed;
    size_t next = 0;
    int done = 0;

    auto finish = [&](Running& r, bool ok, const std::string& why) {
        std::cout << r.stdoutText << std::flush;
        std::cerr << r.stderrText;
        ++done;
        const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
        const auto left = estimateRemaining(done, total, elapsed);
        std::cerr << prefix << "[" << done << "/" << total << "] " << r.job->input
                  << (ok ? " ok" : " FAILED") << ", elapsed " << formatDuration(elapsed);
        if (left && done < total)
            std::cerr << ", ETA " << formatDuration(*left);
        std::cerr << "\n";
        if (!ok) {
            failed.push_back(r.job->input);
            std::cerr << prefix << "FAILED " << r.job->input << ": " << why << "\n";
        }
        std::cerr.flush();
    };

    std::cerr << prefix << total << " input" << (total == 1 ? "" : "s") << ", " << parallel
              << " in parallel\n";
    while (next < jobs.size() || !running.empty()) {
        while (next < jobs.size() && int(running.size()) < parallel) {
            Running r;
            std::string error;
            const BatchJob& job = jobs[next++];
            if (!spawn(exe, job, r, &error)) {
                r.job = &job;
                finish(r, false, "cannot start " + exe + ": " + error);
                continue;
            }
            std::cerr << prefix << "started " << job.input << "\n";
            running.push_back(std::move(r));
        }
        if (running.empty())
            break;
        std::vector<pollfd> fds;
        for (const Running& r : running) {
            if (r.out >= 0)
                fds.push_back({r.out, POLLIN, 0});
            if (r.err >= 0)
                fds.push_back({r.err, POLLIN, 0});
        }
        if (!fds.empty() && poll(fds.data(), nfds_t(fds.size()), 200) < 0 && errno != EINTR)
            break;
        for (auto it = running.begin(); it != running.end();) {
            Running& r = *it;
            for (const pollfd& p : fds) {
                if (!(p.revents & (POLLIN | POLLHUP | POLLERR)))
                    continue;
                if (p.fd == r.out && r.out >= 0)
                    drain(r.out, r.stdoutText);
                else if (p.fd == r.err && r.err >= 0)
                    drain(r.err, r.stderrText);
            }
            if (r.out >= 0 || r.err >= 0) {
                ++it;
                continue;
            }
            // Both pipes closed: the child has exited (or closed them); reap it.
            int status = 0;
            while (waitpid(r.pid, &status, 0) < 0 && errno == EINTR) {
            }
            const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
            std::string why;
            if (WIFSIGNALED(status))
                why = std::string("killed by signal ") + std::to_string(WTERMSIG(status)) + " (" +
                      strsignal(WTERMSIG(status)) + ")";
            else if (!ok)
                why = "exit " + std::to_string(WEXITSTATUS(status)) + ": " + lastLine(r.stderrText);
            finish(r, ok, why);
            it = running.erase(it);
        }
    }
    if (!failed.empty()) {
        std::cerr << prefix << failed.size() << " of " << total << " inputs failed:";
        for (const std::string& f : failed)
            std::cerr << " " << f;
        std::cerr << "\n";
        return BadInput;
    }
    std::cerr << prefix << "all " << total << " inputs done in "
              << formatDuration(std::chrono::duration<double>(Clock::now() - start).count())
              << "\n";
    return Ok;
}

} // namespace velvet::cli
