#include "core/atomic_file.h"

#include <cerrno>
#include <cstdio>
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

/// Keeps the previous version as "file.bak". A hard link costs nothing and leaves the document in
/// place until the rename replaces it; a copy is the fallback where links are not supported.
bool makeBackup(const fs::path& file, std::string* error) {
    fs::path bak = file;
    bak += ".bak";
    std::error_code ec;
    fs::remove(bak, ec);
    if (::link(file.c_str(), bak.c_str()) == 0)
        return true;
    ec.clear();
    fs::copy_file(file, bak, fs::copy_options::overwrite_existing, ec);
    if (ec) {
        setIf(error, "cannot keep a backup of \"" + file.string() + "\" as \"" + bak.string() +
                         "\": " + ec.message());
        return false;
    }
    return true;
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

bool writeFileAtomically(const fs::path& file, std::string_view data, std::string* error,
                         bool keepBackup) {
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
    std::string tmpName = file.filename().string();
    tmpName.insert(0, 1, '.');
    tmpName += ".XXXXXX";
    std::string tmpl = tmpFolder / tmpName;
    FdGuard fd;
    fd.fd = ::mkstemp(tmpl.data());
    if (fd.fd < 0) {
        setIf(error, "cannot write " + name + ": cannot create a temporary file in " +
                         quotedName(tmpFolder) + ": " + errnoText(errno));
        return false;
    }
    const fs::path tmp = tmpl;
    auto fail = [&](const std::string& what, int err) {
        setIf(error, "cannot write " + name + ": " + what + ": " + errnoText(err));
        ::unlink(tmp.c_str());
        return false;
    };
    // mkstemp creates 0600; keep the mode of the file being replaced, else an ordinary 0644.
    struct stat old {};
    const bool replacing = ::stat(file.c_str(), &old) == 0;
    ::fchmod(fd.fd, replacing ? (old.st_mode & 07777) : 0644);
    if (!writeAll(fd.fd, data))
        return fail("write failed", errno);
    if (::fsync(fd.fd) != 0)
        return fail("flush to disk failed", errno);
    const int closeResult = ::close(fd.fd);
    fd.fd = -1;
    if (closeResult != 0)
        return fail("close failed", errno);
    if (keepBackup && replacing && !makeBackup(file, error)) {
        ::unlink(tmp.c_str());
        return false;
    }
    if (::rename(tmp.c_str(), file.c_str()) != 0)
        return fail("rename failed", errno);
    syncFolder(folder);
    return true;
}

} // namespace velvet
