#include "core/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <sys/stat.h>
#include <system_error>
#include <unistd.h>

namespace velvet {
namespace {

namespace fs = std::filesystem;

std::string describeSize(std::uintmax_t bytes) {
    if (bytes < 1024u * 1024u)
        return std::to_string(bytes) + " bytes";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.1f MB", static_cast<double>(bytes) / (1024.0 * 1024.0));
    return buf;
}

std::string errnoText(int err) {
    return std::error_code(err, std::generic_category()).message();
}

/// The file name in quotes. Built by appending: GCC 12 warns falsely (-Wrestrict) on
/// `"\"" + std::string`.
std::string quotedName(const fs::path& file) {
    std::string out(1, '"');
    out += file.string();
    out += '"';
    return out;
}

void setIf(std::string* out, std::string text) {
    if (out)
        *out = std::move(text);
}

/// Closes a POSIX descriptor on every path out of the writer.
struct FdGuard {
    int fd = -1;
    ~FdGuard() {
        if (fd >= 0)
            ::close(fd);
    }
};

bool writeAll(int fd, std::string_view data) {
    while (!data.empty()) {
        const ssize_t n = ::write(fd, data.data(), data.size());
        if (n < 0) {
            if (errno == EINTR)
                continue;
            return false;
        }
        data.remove_prefix(static_cast<size_t>(n));
    }
    return true;
}

/// Makes the rename itself durable: without syncing the folder a crash can forget the new name.
void syncFolder(const fs::path& folder) {
    const int dfd = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY);
    if (dfd >= 0) {
        ::fsync(dfd);
        ::close(dfd);
    }
}

const std::string kTempMarker = ".velvet-tmp-";

/// ".NAME.velvet-tmp-PID-" — the prefix of every temporary of @p file.
std::string temporaryPrefix(const fs::path& file) {
    std::string prefix(1, '.');
    prefix += file.filename().string();
    prefix += kTempMarker;
    return prefix;
}

/// What a failed system call means for the artist, with the folder named where the folder is
/// the problem (issue 18, "Disks and folders that say no").
std::string reasonFor(int err, const fs::path& folder) {
    switch (err) {
    case ENOENT:
        return "the folder " + quotedName(folder) + " does not exist";
    case ENOTDIR:
        return quotedName(folder) + " is not a folder";
    case EACCES:
    case EPERM:
        return "no permission to write in " + quotedName(folder);
    case EROFS:
        return "the folder " + quotedName(folder) + " is on a read-only file system";
    case ENOSPC:
        return "the disk is full (" + errnoText(err) + ")";
    case EDQUOT:
        return "the disk quota is used up (" + errnoText(err) + ")";
    case EFBIG:
        return "the file would exceed the largest size allowed (" + errnoText(err) + ")";
    default:
        return errnoText(err);
    }
}

/// A hidden name for the temporary of @p file: ".NAME.velvet-tmp-PID-XXXXXX" (mkstemp template).
std::string temporaryTemplate(const fs::path& file) {
    const fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
    return (folder / (temporaryPrefix(file) + std::to_string(::getpid()) + "-XXXXXX")).string();
}

/// Moves FILE.(N-1) to FILE.N … FILE.1 to FILE.2, then keeps @p file as FILE.1. A hard link costs
/// nothing and leaves the document in place until the rename replaces it; a copy is the
/// fallback where links are not supported. Every step leaves the document itself untouched.
bool rotateBackups(const fs::path& file, int generations, std::string* error) {
    std::error_code ec;
    for (int g = generations; g >= 2; --g) {
        const fs::path older = backupPath(file, g - 1);
        if (fs::exists(fs::symlink_status(older, ec)) &&
            ::rename(older.c_str(), backupPath(file, g).c_str()) != 0) {
            setIf(error, "cannot keep a backup of " + quotedName(file) + " as " +
                             quotedName(backupPath(file, g)) + ": " + errnoText(errno));
            return false;
        }
    }
    const fs::path first = backupPath(file, 1);
    fs::remove(first, ec);
    if (::link(file.c_str(), first.c_str()) == 0)
        return true;
    ec.clear();
    fs::copy_file(file, first, fs::copy_options::overwrite_existing, ec);
    if (ec) {
        setIf(error, "cannot keep a backup of " + quotedName(file) + " as " + quotedName(first) +
                         ": " + ec.message());
        return false;
    }
    return true;
}

/// Opens an unnamed temporary file in @p folder (O_TMPFILE). -1 with errno when the file system
/// or kernel has none (EOPNOTSUPP, EISDIR, EINVAL) or the folder refuses (then errno says why).
int openUnnamed(const fs::path& folder, mode_t mode) {
#ifdef O_TMPFILE
    return ::open(folder.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, mode);
#else
    (void)folder;
    (void)mode;
    errno = EOPNOTSUPP;
    return -1;
#endif
}

bool unnamedUnsupported(int err) {
    return err == EOPNOTSUPP || err == EISDIR || err == EINVAL;
}

/// Gives the unnamed file @p fd the name @p name (linkat through /proc/self/fd, which needs no
/// privilege, unlike AT_EMPTY_PATH). -1 with errno on failure (EEXIST when the name is taken).
int linkUnnamed(int fd, const std::string& name) {
    const std::string procPath = "/proc/self/fd/" + std::to_string(fd);
    return ::linkat(AT_FDCWD, procPath.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW);
}

/// A hidden temporary name for @p file to link an unnamed file to: the process id and a counter
/// make it unique among writers; "u" tells it from mkstemp's names when debugging.
std::string unnamedLinkName(const fs::path& file) {
    static std::atomic<unsigned> counter{0};
    std::string name = temporaryTemplate(file);
    name.resize(name.size() - 6);
    name += 'u';
    name += std::to_string(counter++);
    return name;
}

} // namespace

std::optional<std::string> readFileWithLimit(const fs::path& file, std::uintmax_t maxBytes,
                                             std::string* reason) {
    std::error_code ec;
    const fs::file_status status = fs::status(file, ec);
    if (ec || !fs::exists(status)) {
        setIf(reason, ec && ec != std::errc::no_such_file_or_directory
                          ? "cannot be read: " + ec.message()
                          : std::string("no such file"));
        return std::nullopt;
    }
    if (fs::is_directory(status)) {
        setIf(reason, "is a folder, not a file");
        return std::nullopt;
    }
    if (!fs::is_regular_file(status)) {
        setIf(reason, "is not a regular file");
        return std::nullopt;
    }
    // The size is checked before a single byte is read, so a huge or hostile file costs nothing.
    const std::uintmax_t size = fs::file_size(file, ec);
    if (ec) {
        setIf(reason, "cannot be read: " + ec.message());
        return std::nullopt;
    }
    if (size > maxBytes) {
        setIf(reason, "is " + describeSize(size) + " (" + std::to_string(size) +
                          " bytes), more than the " + describeSize(maxBytes) + " limit");
        return std::nullopt;
    }
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        setIf(reason, "cannot be opened: " + errnoText(errno));
        return std::nullopt;
    }
    std::string data(static_cast<size_t>(size), '\0');
    in.read(data.data(), static_cast<std::streamsize>(size));
    data.resize(static_cast<size_t>(in.gcount()));
    if (in.bad()) {
        setIf(reason, "cannot be read: " + errnoText(errno));
        return std::nullopt;
    }
    // The file may have grown since it was measured; the limit holds regardless.
    if (in.peek() != std::ifstream::traits_type::eof()) {
        setIf(reason, "grew while being read, beyond the " + describeSize(maxBytes) + " limit");
        return std::nullopt;
    }
    return data;
}

std::optional<std::string> readWholeFile(const fs::path& file, std::uintmax_t maxBytes,
                                         std::string* error) {
    std::string reason;
    auto data = readFileWithLimit(file, maxBytes, &reason);
    if (!data)
        setIf(error, quotedName(file) + " " + reason);
    return data;
}

fs::path backupPath(const fs::path& file, int generation) {
    fs::path out = file;
    out += "." + std::to_string(generation);
    return out;
}

bool isTemporaryOf(const fs::path& target, const std::string& name) {
    const std::string prefix = temporaryPrefix(target);
    if (name.compare(0, prefix.size(), prefix) != 0)
        return false;
    // PID, a dash, then mkstemp's six characters or "u" and a counter.
    size_t i = prefix.size();
    const size_t digitsStart = i;
    while (i < name.size() && name[i] >= '0' && name[i] <= '9')
        ++i;
    return i > digitsStart && i + 1 < name.size() && name[i] == '-';
}

int sweepStaleTemporaries(const fs::path& target) {
    const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    const std::string prefix = temporaryPrefix(target);
    std::error_code ec;
    int removed = 0;
    const auto now = fs::file_time_type::clock::now();
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (!isTemporaryOf(target, name))
            continue;
        const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
        // A writer that is still running owns its temporary; one that is gone (killed, crashed)
        // left it behind. An hour-old one is stale even if its process id was reused since.
        const bool writerGone =
            pid <= 0 || (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH);
        std::error_code timeEc;
        const auto written = fs::last_write_time(it->path(), timeEc);
        const bool old = !timeEc && now - written > std::chrono::hours(1);
        if ((writerGone || old) && fs::remove(it->path(), timeEc))
            ++removed;
    }
    return removed;
}

bool writeFileAtomically(const fs::path& file, std::string_view data, std::string* error,
                         bool keepBackup) {
    AtomicWriteOptions options;
    options.backupGenerations = keepBackup ? kDefaultBackupGenerations : 0;
    return writeFileAtomically(file, data, error, options);
}

bool writeFileAtomically(const fs::path& file, std::string_view data, std::string* error,
                         const AtomicWriteOptions& options) {
    const std::string name = quotedName(file);
    if (file.filename().empty()) {
        setIf(error, "cannot write " + name + ": not a file name");
        return false;
    }
    std::error_code ec;
    if (fs::is_directory(file, ec)) {
        setIf(error, "cannot write " + name + ": it is a folder");
        return false;
    }
    // The temporary file lives in the target's folder so that the final rename stays on one file
    // system and is therefore atomic: readers see the old document or the new one, never a mix.
    const fs::path folder = file.parent_path();
    const fs::path tmpFolder = folder.empty() ? fs::path(".") : folder;
    // The mode of the file being replaced, else an ordinary 0644.
    struct stat old {};
    const bool replacing = ::stat(file.c_str(), &old) == 0;
    const mode_t mode = replacing ? (old.st_mode & 07777) : 0644;

    FdGuard fd;
    bool unnamed = false;
    // Linking an unnamed file goes through /proc/self/fd (see linkUnnamed): without /proc mounted
    // (some containers) the named temporary is used.
    if (options.allowUnnamedTemporary && ::access("/proc/self/fd", X_OK) == 0) {
        fd.fd = openUnnamed(tmpFolder, mode);
        unnamed = fd.fd >= 0;
        if (!unnamed && !unnamedUnsupported(errno)) {
            setIf(error, "cannot write " + name + ": " + reasonFor(errno, tmpFolder));
            return false;
        }
    }
    std::string tmp;
    if (!unnamed) {
        tmp = temporaryTemplate(file);
        fd.fd = ::mkstemp(tmp.data());
        if (fd.fd < 0) {
            setIf(error, "cannot write " + name + ": " + reasonFor(errno, tmpFolder));
            return false;
        }
        ::fchmod(fd.fd, mode); // mkstemp creates 0600
    }
    auto fail = [&](const std::string& what, int err) {
        setIf(error, "cannot write " + name + ": " + what + ": " + reasonFor(err, tmpFolder));
        if (!tmp.empty())
            ::unlink(tmp.c_str());
        return false;
    };
    if (!writeAll(fd.fd, data))
        return fail("write failed", errno);
    if (::fsync(fd.fd) != 0)
        return fail("flush to disk failed", errno);
    // Temporaries a killed writer of this target left (named ones only: unnamed ones vanish
    // with their process).
    sweepStaleTemporaries(file);
    if (options.backupGenerations > 0 && replacing &&
        !rotateBackups(file, options.backupGenerations, error)) {
        if (!tmp.empty())
            ::unlink(tmp.c_str());
        return false;
    }
    if (unnamed) {
        // A new file is named in one step: nothing to replace, so no temporary name at all.
        if (!replacing && linkUnnamed(fd.fd, file.string()) == 0) {
            ::close(fd.fd);
            fd.fd = -1;
            syncFolder(folder);
            return true;
        }
        tmp = unnamedLinkName(file);
        if (linkUnnamed(fd.fd, tmp) != 0) {
            const int err = errno;
            tmp.clear();
            return fail("cannot name the written file", err);
        }
    }
    const int closeResult = ::close(fd.fd);
    fd.fd = -1;
    if (closeResult != 0)
        return fail("close failed", errno);
    if (::rename(tmp.c_str(), file.c_str()) != 0)
        return fail("rename failed", errno);
    syncFolder(folder);
    return true;
}

} // namespace velvet
