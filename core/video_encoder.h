#pragma once
/// @file video_encoder.h
/// A video from a numbered image sequence through the `ffmpeg` program, when it is installed
/// (Velvet links no video codec; ffmpeg is the tool every pipeline already has).

#include <filesystem>
#include <string>

namespace velvet {

/// The executable @p name as execvp would find it on $PATH; empty when there is none.
std::filesystem::path findProgram(const std::string& name);

/// Whether @p file's extension is a container encodeVideo writes (.mp4, .mov, .mkv).
bool isVideoExtension(const std::filesystem::path& file);

/// The message for a missing ffmpeg (the CLI prints it, the editor shows it).
std::string ffmpegMissingMessage();

/// Encodes frames 0 .. @p frames - 1 of @p pattern (printf-style, core/frame_pattern.h; 8-bit
/// PNG) into @p out at @p fps frames a second: H.264 in yuv420p (what every player reads), odd
/// sizes padded to even ones. ffmpeg writes a hidden temporary beside @p out that is renamed over
/// it only when ffmpeg succeeded, so a failed or killed encode leaves any previous @p out whole
/// (core/atomic_file.h's naming: a later write sweeps a temporary left by a killed process).
/// False + @p error (ffmpeg's last lines) on failure.
bool encodeVideo(const std::string& pattern, int frames, int fps, const std::filesystem::path& out,
                 std::string* error);

} // namespace velvet
