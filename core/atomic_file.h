#pragma once
/// @file atomic_file.h
/// Whole-file reads with a size limit and atomic writes, so a crash never leaves a half-written
/// document and a killed write leaves no litter (issue 18, "Seconds, not a minute").
///
/// A write goes to an unnamed temporary file in the target's folder (Linux O_TMPFILE: the inode
/// has no name until it is complete, so a process killed mid-write leaves nothing behind), is
/// flushed to disk, then given its name: linked straight to the target when there is none yet,
/// else linked to a hidden ".NAME.velvet-tmp-PID-XXXXXX" and renamed over the target (rename(2)
/// is atomic; linkat(2) cannot replace). Where O_TMPFILE is not supported (older kernels, some
/// network file systems) the hidden name is created with mkstemp and renamed the same way; a
/// process killed then may leave that name, and the next write of the same target removes every
/// such temporary whose writing process is gone (sweepStaleTemporaries).
///
/// Saves may keep backup generations, as Blender's "save versions": "FILE.1" is the version the
/// save replaced, "FILE.2" the one before it, and so on.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace velvet {

/// Backup generations a document save keeps by default (Blender's default save versions: 2).
inline constexpr int kDefaultBackupGenerations = 2;

struct AtomicWriteOptions {
    /// Previous versions kept as FILE.1 … FILE.N (0: none).
    int backupGenerations = 0;
    /// Tests only: false forces the named-temporary path (as where O_TMPFILE is unsupported).
    bool allowUnnamedTemporary = true;
};

/// Reads @p file; refuses files larger than @p maxBytes before reading. nullopt + @p error on
/// failure.
std::optional<std::string> readWholeFile(const std::filesystem::path& file, std::uintmax_t maxBytes,
                                         std::string* error);
/// As readWholeFile, but @p reason gets the failure without the file name ("is a folder", "is
/// 50.0 MB, more than the 16.0 MB limit"), for callers that report the file separately.
std::optional<std::string> readFileWithLimit(const std::filesystem::path& file,
                                             std::uintmax_t maxBytes, std::string* reason);
/// Writes @p data to @p file atomically (see the file comment). False + @p error (one line naming
/// the file and the reason: "no space left on device", "the folder … does not exist", …) on
/// failure, and then the previous file and its backups are untouched.
bool writeFileAtomically(const std::filesystem::path& file, std::string_view data,
                         std::string* error, const AtomicWriteOptions& options);
/// As above; @p keepBackup keeps kDefaultBackupGenerations previous versions (FILE.1, FILE.2).
bool writeFileAtomically(const std::filesystem::path& file, std::string_view data,
                         std::string* error, bool keepBackup = false);

/// The name of backup generation @p generation (1 = newest) of @p file: "FILE.1".
std::filesystem::path backupPath(const std::filesystem::path& file, int generation);
/// True when @p name (a file name, no folder) is one of the hidden temporaries a write of
/// @p target creates (".NAME.velvet-tmp-PID-XXXXXX").
bool isTemporaryOf(const std::filesystem::path& target, const std::string& name);
/// Removes the temporaries of @p target left by writers that are no longer running (or older
/// than an hour, in case the process id was reused). Returns how many were removed.
int sweepStaleTemporaries(const std::filesystem::path& target);

} // namespace velvet
