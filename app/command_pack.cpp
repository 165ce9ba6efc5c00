// velvet pack / velvet unpack: single-channel material maps into one texture in an engine's
// layout and back (core/channel_packing.h): glTF metallic-roughness, Unreal ORM, Unity HDRP mask
// map, the seed atlas's specular/roughness/metallic.
#include "app/cli.h"
#include "core/channel_packing.h"
#include "core/image.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <system_error>
#include <vector>

namespace velvet::cli {
namespace {

/// One map a layout holds, as the command line names it. HDRP stores smoothness (1 - roughness),
/// so its file is a smoothness map and is inverted on the way in and out.
struct MapFlag {
    std::string flag; ///< option and unpacked file name: "occlusion", "smoothness", …
    Image ChannelMaps::*member;
    bool inverted = false;
};

std::string layoutIds() {
    std::string ids;
    for (int i = 0; i < int(PackLayout::Count); ++i)
        ids += (ids.empty() ? "" : ", ") + std::string(packLayoutId(PackLayout(i)));
    return ids;
}

/// The maps @p layout holds (in a fixed order). Taken from the packing code itself: unpacking a
/// 1x1 image of the layout fills exactly the maps the layout has a channel for.
std::vector<MapFlag> layoutMaps(PackLayout layout) {
    Image probe(1, 1, 4);
    ChannelMaps maps;
    unpackChannels(layout, probe, maps, nullptr);
    const bool smoothness = layout == PackLayout::HdrpMaskMap;
    const std::vector<MapFlag> all{
        {"occlusion", &ChannelMaps::occlusion},
        {smoothness ? "smoothness" : "roughness", &ChannelMaps::roughness, smoothness},
        {"metallic", &ChannelMaps::metallic},
        {"specular", &ChannelMaps::specular},
        {"detail", &ChannelMaps::detailMask},
    };
    std::vector<MapFlag> held;
    for (const MapFlag& m : all)
        if (!(maps.*m.member).empty())
            held.push_back(m);
    return held;
}

std::string flagList(const std::vector<MapFlag>& maps) {
    std::string s;
    for (const MapFlag& m : maps)
        s += (s.empty() ? "--" : ", --") + m.flag;
    return s;
}

void invert(Image& image) {
    for (float& v : image.pixels)
        v = 1.0f - v;
}

/// The sample type for @p file: half float for OpenEXR, else 8 bit, or 16 where asked and the
/// format has it (PNG, TIFF).
PixelFormat formatFor(const std::filesystem::path& file, int bits) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".exr")
        return PixelFormat::Half;
    return bits == 16 ? PixelFormat::UInt16 : PixelFormat::UInt8;
}

bool parseBits(const Arguments& args, int& bits) {
    bits = 8;
    if (!args.has("bits"))
        return true;
    const std::string v = args.value("bits");
    if (v == "8" || v == "16") {
        bits = std::stoi(v);
        return true;
    }
    return false;
}

int usage(const std::string& command, const std::string& message) {
    std::cerr << "velvet " << command << ": " << message << "\nRun 'velvet " << command
              << " --help' for usage.\n";
    return UsageError;
}

std::string layoutsHelp() {
    std::ostringstream s;
    s << "Layouts (--layout ID) and the maps each holds:\n";
    for (int i = 0; i < int(PackLayout::Count); ++i) {
        std::string id(packLayoutId(PackLayout(i)));
        s << "  " << id << std::string(id.size() < 12 ? 12 - id.size() : 1, ' ')
          << packLayoutLabel(PackLayout(i)) << "\n"
          << "              maps: " << flagList(layoutMaps(PackLayout(i))) << "\n";
    }
    return s.str();
}

} // namespace

int runPack(const std::vector<std::string>& argv) {
    std::vector<OptionSpec> options{
        {"layout", 'l', true, "ID", "the packed layout (below)"},
        {"out", 'o', true, "FILE", "the packed image (format by extension; .exr is half float)"},
        {"bits", 0, true, "8|16", "bits per sample for PNG and TIFF (default 8)"},
    };
    for (const char* map :
         {"occlusion", "roughness", "smoothness", "metallic", "specular", "detail"})
        options.push_back({map, 0, true, "FILE", "a grey map (a colour file's R is used)"});
    options.push_back({"help", 'h', false, "", "this text"});
    std::string error;
    auto args = parseArguments(argv, options, &error);
    if (!args)
        return usage("pack", error);
    if (args->has("help")) {
        std::cout << "Usage: velvet pack --layout ID --out FILE [--MAP FILE]...\n"
                     "Packs single-channel maps into one texture in an engine's layout. Maps not\n"
                     "given take the neutral value (occlusion 1, roughness 0.5, metallic 0,\n"
                     "specular 0.5, detail 1). All maps must have the same size. The output is\n"
                     "written atomically; nothing is written when an input is missing or bad.\n\n"
                  << optionsHelp(options) << "\n"
                  << layoutsHelp();
        return Ok;
    }
    if (!args->positional.empty())
        return usage("pack", "takes no FILE argument; give each map with its --MAP option");
    if (!args->has("layout") || !args->has("out"))
        return usage("pack", "needs --layout ID and --out FILE");
    const auto layout = packLayoutFromId(args->value("layout"));
    if (!layout)
        return usage("pack",
                     "unknown layout \"" + args->value("layout") + "\"; layouts: " + layoutIds());
    int bits = 8;
    if (!parseBits(*args, bits))
        return usage("pack", "--bits must be 8 or 16");
    const std::vector<MapFlag> maps = layoutMaps(*layout);
    for (const char* map :
         {"occlusion", "roughness", "smoothness", "metallic", "specular", "detail"})
        if (args->has(map) &&
            std::none_of(maps.begin(), maps.end(), [&](const MapFlag& m) { return m.flag == map; }))
            return usage("pack", std::string("--") + map + ": layout " +
                                     std::string(packLayoutId(*layout)) + " holds " +
                                     flagList(maps));
    ChannelMaps inputs;
    bool any = false;
    const MapFlag* first = nullptr; // the first map read, which the others must match in size
    for (const MapFlag& m : maps) {
        if (!args->has(m.flag))
            continue;
        Image& image = inputs.*m.member;
        if (!readImage(args->value(m.flag), image, &error)) {
            std::cerr << "velvet pack: " << error << "\n";
            return BadInput;
        }
        if (m.inverted)
            invert(image); // a smoothness file: roughness = 1 - smoothness
        any = true;
        // Checked here, not left to packChannels, so that the message names the options the user
        // gave (--smoothness, not the roughness channel it becomes) and their files.
        if (!first) {
            first = &m;
        } else if (const Image& f = inputs.*first->member;
                   f.width != image.width || f.height != image.height) {
            auto size = [](const Image& i) {
                return std::to_string(i.width) + "x" + std::to_string(i.height);
            };
            std::cerr << "velvet pack: all maps must have the same size: --" << first->flag << " "
                      << args->value(first->flag) << " is " << size(f) << ", --" << m.flag << " "
                      << args->value(m.flag) << " is " << size(image) << "\n";
            return BadInput;
        }
    }
    if (!any)
        return usage("pack", "give at least one map (" + flagList(maps) + ")");
    Image packed;
    if (!packChannels(*layout, inputs, packed, &error)) {
        std::cerr << "velvet pack: " << error << "\n";
        return BadInput;
    }
    const std::filesystem::path out = args->value("out");
    if (!writeImage(out, packed, formatFor(out, bits), &error)) {
        std::cerr << "velvet pack: " << error << "\n";
        return BadInput;
    }
    std::cout << "wrote " << out.string() << " (" << packLayoutLabel(*layout) << ", "
              << packed.width << "x" << packed.height << ")\n";
    return Ok;
}

int runUnpack(const std::vector<std::string>& argv) {
    const std::vector<OptionSpec> options{
        {"layout", 'l', true, "ID", "the packed image's layout (see 'velvet pack --help')"},
        {"out-dir", 'o', true, "DIR", "folder for the maps (created if needed)"},
        {"format", 'f', true, "EXT", "png (default), tif, exr"},
        {"bits", 0, true, "8|16", "bits per sample for png and tif (default 8)"},
        {"help", 'h', false, "", "this text"},
    };
    std::string error;
    auto args = parseArguments(argv, options, &error);
    if (!args)
        return usage("unpack", error);
    if (args->has("help")) {
        std::cout
            << "Usage: velvet unpack --layout ID IN --out-dir DIR [--format EXT]\n"
               "Splits a packed texture into one grey image per map the layout holds,\n"
               "named after the map (DIR/occlusion.png, DIR/roughness.png, …; HDRP's\n"
               "smoothness channel as DIR/smoothness.png). Files are written only inside DIR,\n"
               "all or nothing: when one cannot be written, none is left behind.\n\n"
            << optionsHelp(options) << "\n"
            << layoutsHelp();
        return Ok;
    }
    if (args->positional.size() != 1)
        return usage("unpack", "needs exactly one packed image IN");
    if (!args->has("layout") || !args->has("out-dir"))
        return usage("unpack", "needs --layout ID and --out-dir DIR");
    const auto layout = packLayoutFromId(args->value("layout"));
    if (!layout)
        return usage("unpack",
                     "unknown layout \"" + args->value("layout") + "\"; layouts: " + layoutIds());
    const std::string format = args->value("format", "png");
    if (format != "png" && format != "tif" && format != "exr")
        return usage("unpack", "--format must be png, tif or exr");
    int bits = 8;
    if (!parseBits(*args, bits))
        return usage("unpack", "--bits must be 8 or 16");
    Image packed;
    if (!readImage(args->positional[0], packed, &error)) {
        std::cerr << "velvet unpack: " << error << "\n";
        return BadInput;
    }
    ChannelMaps maps;
    if (!unpackChannels(*layout, packed, maps, &error)) {
        std::cerr << "velvet unpack: " << args->positional[0] << ": " << error << "\n";
        return BadInput;
    }
    const std::filesystem::path dir = args->value("out-dir");
    std::error_code ec;
    const bool dirExisted = std::filesystem::exists(dir, ec);
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir)) {
        std::cerr << "velvet unpack: " << dir.string() << ": cannot create the folder"
                  << (ec ? " (" + ec.message() + ")" : "") << "\n";
        return BadInput;
    }
    // All or nothing ("exit 2, nothing written"): every target is checked before anything is
    // written, every map is written under a hidden staging name first, and only when all are
    // written are they renamed into place. Any failure removes what this run wrote. The names
    // are fixed map names, never taken from the input, so every file lands in DIR.
    struct Target {
        std::filesystem::path file, staged;
        bool existed = false;
        bool placed = false;
    };
    std::vector<Target> targets;
    const std::vector<MapFlag> held = layoutMaps(*layout);
    for (const MapFlag& m : held) {
        Target t;
        t.file = dir / (m.flag + "." + format);
        t.staged = dir / ("." + m.flag + ".unpacking." + format);
        const auto status = std::filesystem::symlink_status(t.file, ec);
        t.existed = std::filesystem::exists(status);
        if (t.existed && !std::filesystem::is_regular_file(status)) {
            std::cerr << "velvet unpack: " << t.file.string()
                      << ": exists and is not a regular file; nothing was written\n";
            if (!dirExisted)
                std::filesystem::remove(dir, ec);
            return BadInput;
        }
        targets.push_back(t);
    }
    auto undo = [&](const std::string& message) {
        for (const Target& t : targets) {
            std::filesystem::remove(t.staged, ec);
            if (t.placed && !t.existed)
                std::filesystem::remove(t.file, ec);
        }
        if (!dirExisted)
            std::filesystem::remove(dir, ec); // only when empty
        std::cerr << "velvet unpack: " << message << "\n";
        return BadInput;
    };
    for (size_t i = 0; i < held.size(); ++i) {
        Image map = maps.*held[i].member;
        if (held[i].inverted)
            invert(map); // back to the file's smoothness
        if (!writeImage(targets[i].staged, map, formatFor(targets[i].file, bits), &error))
            return undo(error + "; nothing was written");
    }
    for (Target& t : targets) {
        std::filesystem::rename(t.staged, t.file, ec);
        if (ec)
            return undo(t.file.string() + ": " + ec.message() + "; the other maps were removed");
        t.placed = true;
    }
    for (const Target& t : targets)
        std::cout << "wrote " << t.file.string() << "\n";
    return Ok;
}

} // namespace velvet::cli
