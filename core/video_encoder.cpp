#include "core/video_encoder.h"

#include "core/atomic_file.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <spawn.h>
#include <sstream>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace velvet {
namespace fs = std::filesystem;
namespace {

std::string lowerExtension(const fs::path& file) {
    std::string ext = file.extension().string();
    for (char& c : ext)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

/// ffmpeg's muxer for the extension (the temporary's name has none ffmpeg could read).
const char* muxerFor(const std::string& ext) {
    if (ext == ".mov")
        return "mov";
    if (ext == ".mkv")
        return "matroska";
    return "mp4";
}

/// The last @p maxLines non-empty lines of @p text, joined with "; ".
std::string lastLines(const std::string& text, int maxLines) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (!line.empty())
            lines.push_back(line);
    std::string out;
    for (size_t i = lines.size() > size_t(maxLines) ? lines.size() - size_t(maxLines) : 0;
         i < lines.size(); ++i)
        out += (out.empty() ? "" : "; ") + lines[i];
    return out;
}

} // namespace

fs::path findProgram(const std::string& name) {
    const char* path = std::getenv("PATH");
    std::istringstream dirs(path ? path : "/usr/local/bin:/usr/bin:/bin");
    for (std::string dir; std::getline(dirs, dir, ':');) {
        const fs::path candidate = fs::path(dir.empty() ? "." : dir) / name;
        struct stat st {};
        if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
            ::access(candidate.c_str(), X_OK) == 0)
            return candidate;
    }
    return {};
}

bool isVideoExtension(const fs::path& file) {
    const std::string ext = lowerExtension(file);
    return ext == ".mp4" || ext == ".mov" || ext == ".mkv";
}

std::string ffmpegMissingMessage() {
    return "--video needs the ffmpeg program, which is not on PATH (install it, e.g. "
           "'apt install ffmpeg'; the frames themselves need no ffmpeg)";
}

bool encodeVideo(const std::string& pattern, int frames, int fps, const fs::path& out,
                 std::string* error) {
    auto fail = [&](const std::string& message) {
        if (error)
            *error = out.string() + ": " + message;
        return false;
    };
    const fs::path ffmpeg = findProgram("ffmpeg");
    if (ffmpeg.empty())
        return fail(ffmpegMissingMessage());
    sweepStaleTemporaries(out);
    // A hidden temporary named as core/atomic_file.h names its own, so a killed encode's litter
    // is swept by the next write of the same video.
    const fs::path folder = out.parent_path().empty() ? fs::path(".") : out.parent_path();
    std::string temporary = (folder / ("." + out.filename().string() + ".velvet-tmp-" +
                                       std::to_string(::getpid()) + "-XXXXXX"))
                                .string();
    const int fd = ::mkstemp(temporary.data());
    if (fd < 0)
        return fail(std::string("cannot create a temporary file beside it: ") +
                    std::strerror(errno));
    ::close(fd);
    char logName[] = "/tmp/velvet-ffmpeg-XXXXXX";
    const int logFd = ::mkstemp(logName);
    if (logFd < 0) {
        fs::remove(temporary);
        return fail(std::string("cannot create ffmpeg's log file: ") + std::strerror(errno));
    }
    const std::string program = ffmpeg.string(), rate = std::to_string(fps),
                      count = std::to_string(frames), muxer = muxerFor(lowerExtension(out));
    // -start_number 0: frames are numbered from 0 (core/turntable.h); -frames:v stops at the
    // turntable's own frames even when older numbered files follow them in the folder.
    std::vector<std::string> args = {program,
                                     "-hide_banner",
                                     "-nostdin",
                                     "-loglevel",
                                     "error",
                                     "-y",
                                     "-framerate",
                                     rate,
                                     "-start_number",
                                     "0",
                                     "-i",
                                     pattern,
                                     "-frames:v",
                                     count,
                                     "-vf",
                                     "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                     "-c:v",
                                     "libx264",
                                     "-pix_fmt",
                                     "yuv420p",
                                     "-movflags",
                                     "+faststart",
                                     "-f",
                                     muxer,
                                     temporary};
    std::vector<char*> argv;
    for (std::string& a : args)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, logFd, 1);
    posix_spawn_file_actions_adddup2(&actions, logFd, 2);
    pid_t pid = 0;
    const int spawned =
        ::posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(logFd);
    int status = 0;
    if (spawned == 0)
        while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
    std::ifstream logStream(logName);
    std::stringstream log;
    log << logStream.rdbuf();
    ::unlink(logName);
    std::error_code ec;
    if (spawned != 0) {
        fs::remove(temporary, ec);
        return fail("cannot start " + program + ": " + std::strerror(spawned));
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        fs::remove(temporary, ec);
        const std::string why = lastLines(log.str(), 3);
        return fail(program + " failed" +
                    (WIFEXITED(status)
                         ? " (exit status " + std::to_string(WEXITSTATUS(status)) + ")"
                         : std::string(" (killed by a signal)")) +
                    (why.empty() ? std::string() : ": " + why));
    }
    ::chmod(temporary.c_str(), 0644); // mkstemp made it 0600; a video is for sharing
    fs::rename(temporary, out, ec);
    if (ec) {
        fs::remove(temporary, ec);
        return fail("cannot rename the encoded video into place: " + ec.message());
    }
    return true;
}

} // namespace velvet
