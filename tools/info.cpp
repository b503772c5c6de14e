// heightpack info: what a texture file holds, level by level.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <iostream>

#include "heightpack/bake/material.hpp"

#include "heightpack/core/parallel.hpp"
#include "heightpack/io/engine_support.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/info.hpp"
#include "heightpack/io/threads.hpp"

#include "command.hpp"
#include "enum_option.hpp"

namespace heightpack::cli {

namespace {

class InfoCommand final : public Command {
public:
    CLI::App* attach(CLI::App& app) override {
        CLI::App* cmd = app.add_subcommand("info", "describe a texture: size, levels, layout, wrap, filter, "
                                                   "scale/offset, min/max/mean per level");
        cmd->add_option("input", input_, "an EXR, KTX2 or DDS heightpack wrote, or any image; NAME.EXT for a sequence "
                                         "NAME.0000.EXT, NAME.0001.EXT, ...; or a material.json 'heightpack build' wrote")
            ->required();
        addEnumOption(*cmd, "--engine", engines_,
                      "say whether the file loads as stored in these engines (three, babylon, unreal, unity, godot; "
                      "repeat or separate with commas): a WARNING line for each that will not, with a format it does load");
        addCommonOptions(*cmd);
        cmd->footer(
            "Examples:\n  heightpack info out/swell.exr\n  heightpack info out/swell.exr --json\n"
            "  heightpack info out/ripple_seq.exr   (the frames out/ripple_seq.0000.exr ...)\n"
            "  heightpack info out/swell.ktx2 --engine three,godot\n"
            "  heightpack info out/ocean/material.json   (what a build made: every texture and its parameters)\n"
            "Engines: what each loader reads, with its source, is in docs/formats.md, 'Which engine loads what'.\n");
        return cmd;
    }

    ExitCode run() override {
        setLibraryThreads(common_.threads);
        // A build's description, or the manifest it was built from, rather than a texture.
        const std::string ext = lowerExtension(input_);
        if (ext == ".json") return runMaterial();
        if (ext == ".toml")
            return fail({ErrorKind::InconsistentOptions, input_, "is a material manifest, not a texture",
                         "build it with 'heightpack build " + input_ + " -o FOLDER', then 'heightpack info "
                         "FOLDER/material.json' describes what it made"});
        // A sequence: frame 0 described in full, then a line per frame.
        const std::vector<std::string> frames = expandSequence(input_);
        if (frames.size() > 1 || frames.front() != input_) return runSequence(frames);
        auto info = readFileInfo(input_, /*silenceDecoderMessages=*/true);
        if (!info) return fail(info.error());
        if (common_.json) {
            nlohmann::json j = toJson(*info);
            if (!engines_.empty()) j["engines"] = enginesJson(*info);
            printJson(j);
        } else if (!common_.quiet) {
            printText(*info);
            printEngines(*info);
        }
        return ExitCode::Ok;
    }

private:
    ExitCode runSequence(const std::vector<std::string>& frames) const {
        std::vector<FileInfo> infos;
        for (const std::string& frame : frames) {
            auto info = readFileInfo(frame, /*silenceDecoderMessages=*/true);
            if (!info) return fail(info.error());
            infos.push_back(std::move(*info));
        }
        if (common_.json) {
            nlohmann::json all = nlohmann::json::array();
            for (const FileInfo& info : infos) all.push_back(toJson(info));
            printJson({{"command", "info"}, {"path", input_}, {"sequence", true}, {"frameCount", infos.size()},
                       {"frames", all}});
            return ExitCode::Ok;
        }
        if (common_.quiet) return ExitCode::Ok;
        std::printf("%s: a sequence of %zu frame%s, %s .. %s\n", input_.c_str(), infos.size(),
                    infos.size() == 1 ? "" : "s", frames.front().c_str(), frames.back().c_str());
        printText(infos.front());
        std::printf("  %-5s %-11s %12s %12s %12s   (level 0, channel %s)\n", "frame", "size", "min", "max", "mean",
                    infos.front().levels.front().channels.front().name.c_str());
        for (size_t f = 0; f < infos.size(); ++f) {
            const LevelInfo& l = infos[f].levels.front();
            const ChannelStats& c = l.channels.front();
            const std::string size = std::to_string(l.width) + "x" + std::to_string(l.height);
            std::printf("  %-5zu %-11s %12.6g %12.6g %12.6g\n", f, size.c_str(), c.min, c.max, c.mean);
        }
        return ExitCode::Ok;
    }

    ExitCode runMaterial() const {
        auto material = readMaterial(input_);
        if (!material) return fail(material.error());
        if (common_.json)
            printJson({{"command", "info"}, {"path", input_}, {"material", nlohmann::json::parse(materialJson(*material))}});
        else if (!common_.quiet)
            printMaterial(*material);
        return ExitCode::Ok;
    }

    // A number as material.json holds it: the shortest text that reads back as the same double.
    static std::string number(double v) {
        char text[32];
        const auto end = std::to_chars(text, text + sizeof text, v).ptr;
        return std::string(text, end);
    }

    // layout: the map's, where it has one (heights, normals).
    static std::string textureText(const MaterialTexture& t, std::optional<Layout> layout = std::nullopt) {
        std::string text = t.file + ", " + std::to_string(t.width) + "x" + std::to_string(t.height) + ", " +
                           std::to_string(t.levels) + (t.levels == 1 ? " level" : " levels");
        if (t.frames > 1) text += ", " + std::to_string(t.frames) + " frames";
        if (layout) text += std::string(", ") + nameOf(*layout);
        return text + ", " + pixelTypeName(t.pixelType.value_or(PixelType::Float));
    }

    void printMaterial(const MaterialDescription& m) const {
        std::printf("%s: material '%s', made by %s from %s\n", input_.c_str(), m.name.c_str(), m.generator.c_str(),
                    m.manifest.c_str());
        auto row = [](const std::string& what, const std::string& texture, const std::string& parameters) {
            std::printf("  %-26s %s; %s\n", what.c_str(), texture.c_str(), parameters.c_str());
        };
        for (const DisplacementLayer& d : m.displacement) {
            std::string p = "tile " + number(d.tileSize) + " m, amplitude " + number(d.amplitude) + " m, scroll " +
                            number(d.scroll[0]) + "," + number(d.scroll[1]) + " tiles/s, " + nameOf(d.wrap) + ", " +
                            nameOf(d.filter);
            if (d.loopPeriod > 0) p += ", loop " + number(d.loopPeriod) + " s";
            if (d.shift) p += ", choppiness " + number(d.choppiness);
            if (d.foam) p += ", foam layer";
            row("displacement '" + d.name + "'", textureText(d.texture, d.layout), p);
        }
        if (const auto& n = m.normals)
            row("normals '" + n->name + "'", textureText(n->texture, n->layout),
                "tile " + number(n->tileSize) + " m, height " + number(n->heightRange) + " m, " + nameOf(n->convention) +
                    ", alpha " + nameOf(n->alpha) + ", " + std::to_string(n->octaves.size()) +
                    (n->octaves.size() == 1 ? " octave" : " octaves"));
        if (const auto& f = m.fresnel)
            row("fresnel '" + f->name + "'", textureText(f->texture),
                "ior " + number(f->ior) + ", " + nameOf(f->model) + ", index " + nameOf(f->index));
        if (const auto& f = m.foam)
            row("foam '" + f->name + "'", f->texture ? textureText(*f->texture) : "no texture (the renderer's own pattern)",
                "from " + number(f->h0) + " m to " + number(f->hmax) + " m, tile " + number(f->tileSize) + " m");
        std::printf("  each texture: 'heightpack info FILE' (files are beside %s); all of them: 'heightpack-view %s'\n",
                    input_.c_str(), input_.c_str());
    }

    // Metres per unit of a height file's lookup errors, when it records its height range; 0 otherwise
    // (stored units, or normal units for a normal map).
    static double metresPerUnit(const FileInfo& info) {
        const TextureDescription& d = info.description;
        return d.isHeights() ? d.units.heightRange.value_or(0.0) : 0.0;
    }

    // What a file's lookup errors are counted in when not metres: a normal map's components, else the
    // stored values.
    static const char* unitsOf(const FileInfo& info) {
        return info.description.kind == TextureKind::Normals ? "normal" : "stored";
    }

    static nlohmann::json toJson(const FileInfo& info) {
        nlohmann::json attributes = nlohmann::json::object();
        for (const auto& [k, v] : info.attributes) attributes[k] = v;
        const double metres = metresPerUnit(info);
        nlohmann::json levels = nlohmann::json::array();
        size_t gpuTotal = 0;
        nlohmann::json worst = 0.0;  // null once a level's error is unknown
        for (size_t i = 0; i < info.levels.size(); ++i) {
            const LevelInfo& l = info.levels[i];
            nlohmann::json channels = nlohmann::json::array();
            for (const ChannelStats& c : l.channels)
                channels.push_back({{"name", c.name}, {"min", c.min}, {"max", c.max}, {"mean", c.mean}});
            nlohmann::json error = nullptr;
            if (l.lookupError) error = *l.lookupError * (metres > 0.0 ? metres : 1.0);
            gpuTotal += l.gpuBytes;
            if (error.is_null()) worst = nullptr;
            else if (!worst.is_null()) worst = std::max(worst.get<double>(), error.get<double>());
            levels.push_back({{"level", i}, {"width", l.width}, {"height", l.height}, {"gpuBytes", l.gpuBytes},
                              {"lookupError", error}, {"channels", channels}});
            // Block formats: the decoded error's RMS (units as lookupError) and, for xy normals, the angles.
            if (l.rmsError) levels.back()["rmsError"] = *l.rmsError * (metres > 0.0 ? metres : 1.0);
            if (l.angleError) levels.back()["angleErrorDegrees"] = *l.angleError;
            if (l.rmsAngleError) levels.back()["rmsAngleErrorDegrees"] = *l.rmsAngleError;
        }
        const TextureDescription& d = info.description;
        auto text = [&](const char* name) {
            const std::string v = findAttribute(info, name);
            return v.empty() ? nlohmann::json(nullptr) : nlohmann::json(v);
        };
        return {
            {"command", "info"},
            {"path", info.path},
            {"format", info.format},
            {"pixelType", info.pixelType},
            {"channels", info.channelNames},
            // An array texture's layers in order (KTX2, DDS); empty for a single texture.
            {"layers", info.layerNames},
            {"tiled", info.storedInTiles},
            {"tileWidth", info.storageTileWidth},
            {"tileHeight", info.storageTileHeight},
            {"width", info.levels.empty() ? 0 : info.levels[0].width},
            {"height", info.levels.empty() ? 0 : info.levels[0].height},
            {"levelCount", info.levels.size()},
            // From the typed description, through the name tables: a word the schema does not list never
            // gets this far (describeTexture refuses it).
            {"layout", d.kind == TextureKind::Image ? nlohmann::json(nullptr) : nlohmann::json(layoutWord(d))},
            {"wrap", d.wrapRecorded ? nlohmann::json(attributeText(d.wrap)) : nlohmann::json(nullptr)},
            {"filter", d.filter ? nlohmann::json(attributeText(*d.filter)) : nlohmann::json(nullptr)},
            {"heightScale", text(attr::heightScale.name)},
            {"heightOffset", text(attr::heightOffset.name)},
            {"gpuBytes", gpuTotal},
            // The worst lookup error against the float chain: 0 for float texels, as recorded for half and
            // uint16, null where the file records none (DDS).
            {"lookupError", {{"units", metres > 0.0 ? "m" : unitsOf(info)},
                             {"worst", worst}}},
            {"levels", levels},
            {"attributes", attributes},
        };
    }

    static void printText(const FileInfo& info) {
        const LevelInfo& top = info.levels.front();
        std::printf("%s: %s, %dx%d, %zu level%s, %s", info.path.c_str(), info.format.c_str(), top.width, top.height,
                    info.levels.size(), info.levels.size() == 1 ? "" : "s", info.pixelType.c_str());
        std::string channels;
        for (const auto& n : info.channelNames) channels += (channels.empty() ? "" : ",") + n;
        std::printf(" %s", channels.c_str());
        if (!info.layerNames.empty()) {
            std::string layers;
            for (const auto& n : info.layerNames) layers.append(layers.empty() ? "" : ", ").append(n);
            std::printf(", an array of %zu layers: %s", info.layerNames.size(), layers.c_str());
        }
        if (info.storedInTiles) std::printf(", tiled %dx%d", info.storageTileWidth, info.storageTileHeight);
        std::printf("\n");
        // Every heightpack attribute, in the order the file lists them.
        const std::string prefix = attr::kPrefix;
        for (const auto& [key, value] : info.attributes)
            if (key.rfind(prefix, 0) == 0) std::printf("  %-13s %s\n", key.substr(prefix.size()).c_str(), value.c_str());
        for (const auto& [key, value] : info.attributes)  // KTX2's own keys: KTXwriter, KTXwriterScParams
            if (key.rfind("KTX", 0) == 0) std::printf("  %-13s %s\n", key.c_str(), value.c_str());
        // Heights are channel 0 in every layout heightpack writes (R of a packed texel is H(i,j)).
        const double metres = metresPerUnit(info);
        std::printf("  %-5s %-11s %12s %12s %12s %11s %13s   (channel %s; lookup error%s)\n", "level", "size", "min",
                    "max", "mean", "gpu bytes", "lookup error", top.channels.front().name.c_str(),
                    metres > 0.0 ? " in metres" : (std::string(" in ") + unitsOf(info) + " units, n/a: not recorded").c_str());
        for (size_t i = 0; i < info.levels.size(); ++i) {
            const LevelInfo& l = info.levels[i];
            const ChannelStats& c = l.channels.front();
            const std::string size = std::to_string(l.width) + "x" + std::to_string(l.height);
            char error[32] = "n/a";
            if (l.lookupError) std::snprintf(error, sizeof error, "%.3g", *l.lookupError * (metres > 0.0 ? metres : 1.0));
            std::printf("  %-5zu %-11s %12.6g %12.6g %12.6g %11zu %13s", i, size.c_str(), c.min, c.max, c.mean,
                        l.gpuBytes, error);
            // Block formats: what the blocks decode to against the float chain, as recorded when written.
            if (l.rmsError) std::printf("  rms %.3g", *l.rmsError * (metres > 0.0 ? metres : 1.0));
            if (l.angleError && l.rmsAngleError)
                std::printf("  angle worst %.3g, rms %.3g deg", *l.angleError, *l.rmsAngleError);
            std::printf("\n");
        }
    }

    nlohmann::json enginesJson(const FileInfo& info) const {
        nlohmann::json all = nlohmann::json::array();
        for (Engine e : engines_) {
            const EngineVerdict v = engineSupport(e, info, static_cast<int>(info.levels.size()));
            all.push_back({{"engine", nameOf(e)}, {"support", nameOf(v.support)}, {"why", v.why},
                           {"alternative", v.alternative.empty() ? nlohmann::json(nullptr) : nlohmann::json(v.alternative)}});
        }
        return all;
    }

    // One line per engine asked about; those that will not load the file as stored start with WARNING.
    void printEngines(const FileInfo& info) const {
        for (Engine e : engines_) {
            const EngineVerdict v = engineSupport(e, info, static_cast<int>(info.levels.size()));
            const bool warn = v.support == EngineSupport::Refuses || v.support == EngineSupport::Partial;
            std::printf("  %s%s: %s: %s%s\n", warn ? "WARNING " : "", nameOf(e), nameOf(v.support), v.why.c_str(),
                        v.alternative.empty() ? "" : ("; it loads " + v.alternative).c_str());
        }
    }

    std::string input_;
    std::vector<Engine> engines_;
};

}  // namespace

std::unique_ptr<Command> makeInfoCommand() { return std::make_unique<InfoCommand>(); }

}  // namespace heightpack::cli
