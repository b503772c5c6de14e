// heightpack normal: a height map in, a tangent-space normal map (mip-mapped EXR or 8-bit PNG) out.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "heightpack/bake/normal_job.hpp"
#include "heightpack/core/parallel.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/threads.hpp"
#include "heightpack/version.hpp"

#include "command.hpp"
#include "enum_option.hpp"
#include "texture_options.hpp"

namespace heightpack::cli {

namespace {

class NormalCommand final : public Command {
public:
    CLI::App* attach(CLI::App& app) override {
        CLI::App* cmd = app.add_subcommand("normal", "derive a tangent-space normal map from a height map, in world units");
        cmd->add_option("input", input_, "height map (any format pack reads)")->required();
        cmd->add_option("-o,--output", output_, "normal map to write: .exr, .ktx2 or .dds (mip-mapped) or .png (8-bit)")
            ->required();
        cmd->add_option("--tile-size", tileSize_, "the tile's width in metres, or width,height (square texels if "
                                                  "only the width is given)")
            ->required()
            ->check(lengthPairValidator(1e5));
        addLengthOption(*cmd, "--height", options_.normal.heightRange, 1e3,
                        "how far a stored 1.0 stands above a stored 0.0, in metres (the viewer's displacement amplitude)")
            ->required();
        addEnumOption(*cmd, "--kernel", options_.normal.kernel, "slope kernel; each measures a plane's slope exactly");
        addEnumOption(*cmd, "--wrap", options_.normal.wrap, "periodic: no seam at the tile edge; clamp: one-sided at the border");
        addEnumOption(*cmd, "--filter", options_.filter, "filter of the height mip chain each level's normals come from");
        addEnumOption(*cmd, "--convention", options_.normal.convention,
                      "opengl: green toward the top of the image; directx: flipped");
        CLI::Option* heightAlpha = cmd->add_flag("--height-in-alpha", heightInAlpha_,
                                                 "store the height (stored value) in alpha, as the D3D11 demo does");
        cmd->add_flag("--variance-in-alpha", varianceInAlpha_,
                      "store the slope variance each level lost to filtering in alpha (Toksvig-style)")
            ->excludes(heightAlpha);
        formatOption_ = addEnumOption(*cmd, "--format", format_, "exr or png8 (default: from the output's extension)")
                            ->default_str("");
        compressionOption_ =
            cmd->add_option("--compression", compression_,
                            "EXR compression, by default none for float normals (zip saves 1-5% of their bytes at "
                            "3-4x the time) and zip for half or auto (it halves them); for .ktx2 none or zstd")
                ->check(CLI::IsMember(compressionNames()));
        addPixelTypeOption(*cmd, pixelType_, true, &tolerance_,
                           "with --pixel-type auto: the worst lookup error allowed over the chain; a number in normal "
                           "units (0.001), an angle (0.5deg) between a stored normal and its own, or a length (1mm, "
                           "0.5cm): the tilt a height error that large makes across one texel, length / texel size");
        addBlockChoiceOption(*cmd, options_.storage.allowBlockCompression);
        addEnumOption(*cmd, "--layout", options_.layout,
                      "rgb: x, y, z; xy: two channels, z rebuilt in the shader as sqrt(1 - x^2 - y^2) (mip-mapped "
                      "outputs, no alpha)",
                      {Layout::Rgb, Layout::Xy});
        addChannelOption(*cmd, channel_);
        cmd->add_option("--resize", resize_, "none: refuse a map whose sides are not powers of two (a .png takes any "
                                              "size); pow2: resample it up to the next ones first")
            ->capture_default_str()
            ->check(CLI::IsMember({"none", "pow2"}));
        addCommonOptions(*cmd);
        cmd->footer(
            "Examples:\n"
            "  heightpack normal examples/maps/ripple.png --tile-size 8m --height 0.15m -o out/ripple_n.exr\n"
            "  heightpack normal ripple.png --tile-size 8m --height 0.15m --format png8 --convention directx "
            "-o ripple_n.png\n"
            "  heightpack normal ripple.png --tile-size 8m --height 0.15m --height-in-alpha -o ripple_nh.exr\n"
            "  heightpack normal ripple.png --tile-size 8m --height 0.15m --layout xy -o ripple_n.ktx2\n"
            "  heightpack normal ripple.png --tile-size 8m --height 0.15m --pixel-type auto --tolerance 0.001 "
            "-o ripple_n.dds\n"
            "  heightpack normal ripple.png --tile-size 8m --height 0.15m --layout xy --pixel-type auto "
            "--allow-block-compression --tolerance 2deg -o ripple_n.ktx2\n"
            "Normals are unit xyz in tangent space, z up; the PNG stores 0.5 + 0.5 n.\n");
        return cmd;
    }

    ExitCode run() override {
        if (const ExitCode code = checkOutputs({}, {{output_, "-o", {".exr", ".ktx2", ".dds", ".png"}}});
            code != ExitCode::Ok)
            return code;
        const std::optional<NormalFormat> format =
            outputFormat(formatOption_->count() > 0 ? std::optional(format_) : std::nullopt, output_);
        if (!format) return usage("the output must end in .exr, .ktx2, .dds or .png, matching --format if given");
        NormalJobOptions& o = options_;
        NormalOptions& n = o.normal;
        const auto comma = tileSize_.find(',');
        n.tileWidth = *parseLength(tileSize_.substr(0, comma));
        n.tileHeight = comma == std::string::npos ? 0.0 : *parseLength(tileSize_.substr(comma + 1));
        n.alpha = heightInAlpha_ ? NormalAlpha::Height : varianceInAlpha_ ? NormalAlpha::SlopeVariance : NormalAlpha::None;
        n.threads = common_.threads;
        o.format = *format;
        o.storage.pixelType = requestedPixelType(pixelType_);
        if (o.format == NormalFormat::Png8 && pixelType_ != PixelTypeRequest::Float)
            return usage("--pixel-type is for .exr, .ktx2 and .dds outputs; a PNG normal map is 8-bit");
        // Normal maps' errors are in normal units: a plain number is one, a length the job converts.
        if (const std::string problem = normalTolerance(pixelType_, tolerance_, o.storage, o.toleranceMetres);
            !problem.empty())
            return usage(problem);
        const std::optional<CompressionChoice> compression =
            compressionOption_->count() > 0 ? std::optional(readCompression(compression_)) : std::nullopt;
        o.storage.exrCompression = compression ? compression->exr.value_or(Compression::Zip)
                                       : defaultNormalCompression(o.storage.pixelType,
                                                                  std::max(o.storage.tolerance, o.toleranceMetres));
        if (const std::string problem = checkContainerChoice({output_}, o.storage.pixelType, compression,
                                                             o.storage.supercompression);
            !problem.empty())
            return usage(problem);
        if (const std::string problem = blockLayoutProblem(o.storage.pixelType, options_.layout); !problem.empty())
            return usage(problem);
        if (const std::string problem =
                blockChoiceProblem(pixelType_, o.storage.allowBlockCompression, options_.layout, {output_});
            !problem.empty())
            return usage(problem);
        o.resizeToPowerOfTwo = resize_ == "pow2";
        applyChannel(channel_, o.load);
        o.load.silenceDecoderMessages = true;
        setLibraryThreads(common_.threads);

        // A sequence gets a normal map per frame, numbered like it; --json prints one document for all.
        const std::vector<std::string> inputs = expandSequence(input_);
        std::vector<OutputRule> outputs;
        for (size_t f = 0; f < inputs.size(); ++f)
            outputs.push_back({frameFileName(output_, int(f), int(inputs.size())), "-o", {".exr", ".ktx2", ".dds", ".png"},
                               inputs.size() > 1});
        if (const ExitCode code = checkOutputs(inputs, outputs); code != ExitCode::Ok) return code;
        nlohmann::json sequence = nlohmann::json::array();
        // A sequence's normal maps land together once every frame has succeeded: a bad frame leaves none.
        StagedOutputs staged;
        HeldStdout held(inputs.size() > 1);
        for (size_t f = 0; f < inputs.size(); ++f) {
            const std::string shown = frameFileName(output_, int(f), int(inputs.size()));
            const std::string output = inputs.size() > 1 ? staged.stage(shown) : shown;
            const ExitCode code = normalOne(inputs[f], output, shown, o, inputs.size() > 1 ? &sequence : nullptr);
            if (code != ExitCode::Ok) return code;
        }
        if (Status committed = staged.commit(); !committed) return fail(committed.error());
        held.release();
        if (inputs.size() > 1 && common_.json) printJson({{"command", "normal"}, {"input", input_}, {"frames", sequence}});
        return ExitCode::Ok;
    }

private:
    // Makes one normal map; its JSON report goes to stdout, or into sequence when making frames.
    // shown: the output's name as given (output may be a staged name for it).
    ExitCode normalOne(const std::string& input, const std::string& output, const std::string& shown, NormalJobOptions& o,
                       nlohmann::json* sequence) {
        const NormalOptions& n = o.normal;
        const bool png8 = o.format == NormalFormat::Png8;
        const char* format = formatWord(o.format, shown);
        Progress progress(!common_.quiet, "normal " + std::filesystem::path(input).filename().string(),
                          {{"load", 0.15}, {"mip", 0.1}, {"normal", 0.35}, {"write", 0.4}});
        progress.update("load", 0.0);  // from the start: loading a large map takes seconds
        o.progress = [&](std::string_view stage, double f) { progress.update(stage, f); };
        auto report = makeNormalMap(input, output, o);
        if (!report) return fail(report.error());
        progress.clear();
        NormalReport& r = *report;
        r.output = shown;
        const int width = r.levelSizes[0].first, height = r.levelSizes[0].second;
        // The channels as stored: x, y for xy; x, y, z and alpha (three count as four on a GPU).
        const int channels = r.layout == Layout::Xy ? 2 : n.alpha == NormalAlpha::None ? 3 : 4;
        if (common_.json) {
            const nlohmann::json stored = storedChainJson(r.levelSizes, channels, r.pixelType, r.lookupError, 0.0, "normal");
            const nlohmann::json doc = {{"command", "normal"},
                       {"input", r.input},
                       {"output", r.output},
                       {"format", format},
                       {"tileWidth", n.tileWidth},
                       {"tileHeight", n.tileHeight > 0 ? n.tileHeight : n.tileWidth * r.levelSizes[0].second /
                                                                            r.levelSizes[0].first},
                       {"heightRange", n.heightRange},
                       {"kernel", nameOf(n.kernel)},
                       {"convention", nameOf(n.convention)},
                       {"wrap", nameOf(n.wrap)},
                       {"sourceHash", r.sourceHash},
                       {"resized", r.resized},
                       {"resize", r.resized ? resizeJson(r.source.width, r.source.height, width, height)
                                            : nlohmann::json(nullptr)},
                       {"channel", channelJson(r.source)},
                       {"maxSlopeDegrees", r.maxSlopeDegrees},
                       {"layout", nameOf(r.layout)},
                       {"alpha", nameOf(n.alpha)},
                       {"channels", channels},
                       {"pixelType", png8 ? nlohmann::json("uint8") : stored["pixelType"]},
                       {"pixelTypeRequested", nameOf(pixelType_)},
                       {"tolerance", r.tolerance > 0.0 && !r.toleranceInDegrees ? nlohmann::json(r.tolerance) : nlohmann::json(nullptr)},
                       {"toleranceDegrees", r.tolerance > 0.0 && r.toleranceInDegrees ? nlohmann::json(r.tolerance) : nlohmann::json(nullptr)},
                       {"angleError", r.angleError.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.angleError)},
                       {"gpuBytes", png8 ? nlohmann::json(nullptr) : stored["gpuBytes"]},
                       {"lookupError", png8 ? nlohmann::json(nullptr) : stored["lookupError"]},
                       {"levels", stored["levels"]},
                       {"seconds", r.seconds}};
            if (sequence)
                sequence->push_back(doc);
            else
                printJson(doc);
        } else if (chatty()) {
            std::ostringstream line;
            line << "wrote " << r.output << ": " << r.levelSizes[0].first << "x" << r.levelSizes[0].second << " ("
                 << r.levelSizes.size() << (r.levelSizes.size() == 1 ? " level" : " levels") << "), "
                 << format << ", tile " << n.tileWidth << " m, height " << n.heightRange << " m, " << nameOf(n.kernel) << ", "
                 << nameOf(n.convention) << ", steepest " << std::fixed << std::setprecision(1) << r.maxSlopeDegrees
                 << " deg, ";
            // What was written: rgba with an alpha (its content named), else the layout's channels.
            const std::string stored = channels == 4 ? std::string("rgba (") + nameOf(n.alpha) + " in alpha)"
                                                     : std::string(nameOf(r.layout));
            line << stored << (png8 ? "" : " " + storedChainText(r.pixelType, r.lookupError, 0.0)) << ", ";
            if (!r.angleError.empty())
            {
                line << "worst angle " << std::setprecision(3) << *std::max_element(r.angleError.begin(), r.angleError.end())
                     << " deg";
                if (r.toleranceInDegrees) line << " (tolerance " << std::defaultfloat << r.tolerance << std::fixed << " deg)";
                line << ", ";
            }
            line << std::setprecision(2) << r.seconds << " s";
            std::cout << line.str() << "\n";
            if (r.resized) std::cout << "  note: " << resizeNote(r.source.width, r.source.height, width, height) << "\n";
            printChannelNote(r.source);
        }
        return ExitCode::Ok;
    }

    std::string input_, output_, tileSize_, channel_;
    NormalFormat format_ = NormalFormat::Exr;
    CLI::Option* formatOption_ = nullptr;
    NormalJobOptions options_;
    std::string compression_, resize_ = "none";
    PixelTypeRequest pixelType_ = PixelTypeRequest::Float;
    std::string tolerance_;
    CLI::Option* compressionOption_ = nullptr;
    bool heightInAlpha_ = false, varianceInAlpha_ = false;
};

}  // namespace

std::unique_ptr<Command> makeNormalCommand() { return std::make_unique<NormalCommand>(); }

}  // namespace heightpack::cli
