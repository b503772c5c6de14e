#include "hints.hpp"

#include <filesystem>

#include "heightpack/io/read.hpp"

namespace heightpack::cli {

namespace {

// A word as a POSIX shell reads it back: as it is when it is plain, else in double quotes.
std::string shellWord(const std::string& word) {
    const bool plain = !word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                               "0123456789_-+=.,:/@%") == std::string::npos;
    if (plain) return word;
    std::string quoted = "\"";
    for (char c : word) {
        if (c == '"' || c == '\\' || c == '$' || c == '`') quoted += '\\';
        quoted += c;
    }
    return quoted + "\"";
}

// A TOML basic string holding text.
std::string tomlString(const std::string& text) {
    std::string quoted = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') quoted += '\\';
        quoted += c;
    }
    return quoted + "\"";
}

}  // namespace

std::string manifestReference() {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (const fs::path self = fs::read_symlink("/proc/self/exe", ec); !ec) {
        const fs::path installed = (self.parent_path() / HEIGHTPACK_DOC_FROM_BIN / "manifest.md").lexically_normal();
        if (fs::is_regular_file(installed, ec)) return installed.string();
    }
    const fs::path source = fs::path(HEIGHTPACK_SOURCE_DOCS) / "manifest.md";
    if (fs::is_regular_file(source, ec)) return source.string();
    return "docs/manifest.md in heightpack's source";
}

std::string cliHint(const Error& error) {
    const auto arg = [&](size_t i) { return i < error.fixArgs.size() ? error.fixArgs[i] : std::string(); };
    switch (error.fix) {
        case Fix::None: return error.hint;
        case Fix::ChooseChannel:
            return "choose the height channel with --channel " + joinedNames<ChannelSelect>("|") + " or a channel's name";
        case Fix::ChooseExistingChannel: return "pick one it has with --channel";
        case Fix::ResizeToPowerOfTwo: return "pass --resize pow2 to resample it to " + arg(0);
        case Fix::ResizeOrLevelZeroOnly:
            return "pass --resize pow2 to resample it to " + arg(0) + ", or --format png8 for level 0 alone";
        case Fix::RenamePlainOutput: return "give --emit-plain another name";
        case Fix::FewerJobs: return "use fewer --jobs or --threads";
        case Fix::WriteFloat:
            return "write float samples: an .exr or .tif output without --depth; heightpack never clips or rescales heights";
        case Fix::AddShift:
            return "synthesise it with 'heightpack synth --shift' to an .exr, or leave out --shift";
        case Fix::AddFoam: return "synthesise it with 'heightpack synth --foam' to an .exr, or leave out --foam";
        case Fix::OnePlainChain: return "leave out --emit-plain: with --layout plain the output is the plain chain";
        case Fix::CompanionsNeedExr: return "--" + arg(0) + " writes an .exr only: name the output .exr";
        case Fix::RgbNormalsInPng: return "--layout xy is for mip-mapped .exr, .ktx2 and .dds outputs; a PNG normal map is rgb";
        case Fix::RgbNormalsForAlpha:
            return "--layout xy stores two channels, leaving no alpha for --height-in-alpha or --variance-in-alpha";
        case Fix::VarianceNeedsLevels: return "--variance-in-alpha is for mip-mapped outputs: write .exr";
        case Fix::ManifestReference:
            return arg(0) + (arg(0).empty() ? "" : " ") + "see " + manifestReference() + " for every key";
        case Fix::MakeTileable: {
            // The command as the shell runs it, with every manifest setting that shapes tile's verdict.
            std::string command = "heightpack tile " + shellWord(arg(0)) + " -o " + shellWord(arg(1));
            if (!arg(4).empty()) command += " --channel " + shellWord(arg(4));
            if (!arg(2).empty()) command += " --filter " + arg(2);
            if (!arg(3).empty()) command += " --threshold " + arg(3);
            const std::string frames = arg(6).empty() ? "" : " (every frame of the sequence alike)";
            const std::string channel = arg(4).empty() ? "" : " and remove channel (it holds the heights alone)";
            return "make it tile with '" + command + "'" + frames + ", then set source = " + tomlString(arg(5)) +
                   channel + "; or set tileable = false if it is not meant to tile";
        }
    }
    return error.hint;
}

std::string cliNote(const std::string& note, Fix fix) {
    return fix == Fix::ResizeToPowerOfTwo ? note + " (pack would need --resize pow2)" : note;
}

}  // namespace heightpack::cli
