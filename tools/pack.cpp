// heightpack pack: one height map in, one packed (or plain) mip-mapped texture out: EXR, KTX2 or DDS.
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>

#include "heightpack/bake/pack_job.hpp"
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

class PackCommand final : public Command {
public:
    CLI::App* attach(CLI::App& app) override {
        CLI::App* cmd = app.add_subcommand("pack", "pack a height map into a mip-mapped, 4-neighbour packed (or plain) EXR, KTX2 or DDS");
        cmd->add_option("input", input_, "height map: " + readableFormats() + "; 8/16-bit, half or float")->required();
        cmd->add_option("-o,--output", output_, "packed texture to write: .exr, .ktx2 or .dds (replaced atomically)")
            ->required();
        addChannelOption(*cmd, channel_);
        cmd->add_option("--scale", options_.scale, "stored height = offset + scale * painted value")
            ->capture_default_str()
            ->check(finiteRange(-1e6, 1e6));
        cmd->add_option("--offset", options_.offset, "see --scale")->capture_default_str()->check(finiteRange(-1e6, 1e6));
        addEnumOption(*cmd, "--wrap", options_.mip.wrap, "how filters and neighbours see past the edge");
        addEnumOption(*cmd, "--filter", options_.mip.filter, "mip filter");
        compressionOption_ = cmd->add_option("--compression", compression_,
                                             "EXR compression (lossless only); for .ktx2 none or zstd")
                                 ->capture_default_str()
                                 ->check(CLI::IsMember(compressionNames()));
        addPixelTypeOption(*cmd, pixelType_, true, &tolerance_);
        addBlockChoiceOption(*cmd, options_.storage.allowBlockCompression);
        addLengthOption(*cmd, "--height", options_.heightRange, 1e3,
                        "how far a stored 1.0 stands above a stored 0.0, in metres: recorded, and lookup errors and "
                        "--tolerance are then in metres");
        addEnumOption(*cmd, "--layout", options_.layout,
                      "neighbour4: each texel holds its four neighbours (one fetch per lookup); plain: one channel, "
                      "the height (textureGather, hardware filtering)",
                      {Layout::Neighbour4, Layout::Plain});
        cmd->add_option("--resize", resize_, "none: refuse a map whose sides are not powers of two; pow2: resample it "
                                              "up to the next ones, with the mip filter")
            ->capture_default_str()
            ->check(CLI::IsMember({"none", "pow2"}));
        cmd->add_option("--emit-plain", options_.plainOutput, "also write the unpacked one-channel mip chain here");
        cmd->add_flag("--shift,--displacement", options_.shift,
                      "keep the input's shift, the waves' sideways motion (Dx, Dy, as synth --shift writes): packed "
                      "beside the heights as layers Dx, Dy of the same .exr, or of the same .ktx2/.dds array texture "
                      "(--displacement is its old name)");
        cmd->add_flag("--foam", options_.foam,
                      "keep the input's foam coverage (its Foam channel, as synth --foam writes it): packed beside the "
                      "heights as layer Foam of the same .exr, or the last layer of the same .ktx2/.dds array texture");
        addCommonOptions(*cmd);
        cmd->footer(
            "Examples:\n"
            "  heightpack pack examples/maps/swell.png -o out/swell.exr\n"
            "  heightpack pack swell.tif --channel r --scale 2.5 --offset -1.25 --filter lanczos3 "
            "--compression none -o swell.exr\n"
            "  heightpack pack big.png --resize pow2 -o big.exr\n"
            "  heightpack pack swell.png --pixel-type half -o swell.dds\n"
            "  heightpack pack swell.png --pixel-type auto --tolerance 1mm --height 6m -o swell.ktx2\n"
            "  heightpack pack swell.png --layout plain --pixel-type uint16 -o swell_r16.ktx2\n"
            "  heightpack pack swell.png --layout plain --pixel-type auto --allow-block-compression --tolerance 5mm "
            "--height 6m -o swell.ktx2\n"
            "  heightpack pack sea.####.exr --shift -o sea_packed.exr\n"
            "  heightpack pack sea.####.exr --shift --foam -o sea_packed.exr\n"
            "  heightpack pack sea.####.exr --shift --foam --pixel-type half -o sea.ktx2   (one array: heights, Dx, Dy, Foam)\n"
            "Texel (i,j) of every level holds R=H(i,j) G=H(i+1,j) B=H(i,j+1) A=H(i+1,j+1), wrapped or clamped.\n");
        return cmd;
    }

    ExitCode run() override {
        if (!std::isfinite(options_.scale) || !std::isfinite(options_.offset))
            return usage("--scale and --offset must be finite numbers");
        options_.load.silenceDecoderMessages = true;  // errors come back in the result, as one line
        applyChannel(channel_, options_.load);
        options_.mip.threads = common_.threads;
        const CompressionChoice compression = readCompression(compression_);
        options_.storage.exrCompression = compression.exr.value_or(Compression::Zip);
        options_.storage.pixelType = requestedPixelType(pixelType_);
        if (const std::string problem =
                toleranceInStoredUnits(pixelType_, tolerance_, options_.heightRange, options_.storage.tolerance);
            !problem.empty())
            return usage(problem);
        const std::string containerProblem =
            checkContainerChoice({output_, options_.plainOutput}, options_.storage.pixelType,
                                 compressionOption_->count() > 0 ? std::optional(compression) : std::nullopt,
                                 options_.storage.supercompression);
        if (!containerProblem.empty()) return usage(containerProblem);
        if (const std::string problem = blockLayoutProblem(options_.storage.pixelType, options_.layout); !problem.empty())
            return usage(problem);
        if (const std::string problem = blockChoiceProblem(pixelType_, options_.storage.allowBlockCompression,
                                                           options_.layout, {output_, options_.plainOutput});
            !problem.empty())
            return usage(problem);
        options_.resizeToPowerOfTwo = resize_ == "pow2";
        setLibraryThreads(common_.threads);

        // A sequence (NAME.0000.EXT ...) packs frame by frame into numbered outputs.
        const std::vector<std::string> inputs = expandSequence(input_);
        const int frames = static_cast<int>(inputs.size());
        const std::string plain = options_.plainOutput;
        // A sequence's outputs, and a packed file with its plain twin, land together once every job has
        // succeeded: a bad frame (or a failed twin) leaves none of this run's files behind.
        const bool stage = frames > 1 || !plain.empty();
        std::vector<OutputRule> outputs;
        for (int f = 0; f < frames; ++f) {
            outputs.push_back({frameFileName(output_, f, frames), "-o", {".exr", ".ktx2", ".dds"}, stage});
            if (!plain.empty())
                outputs.push_back({frameFileName(plain, f, frames), "--emit-plain", {".exr", ".ktx2", ".dds"}, stage});
        }
        if (const ExitCode code = checkOutputs(inputs, outputs); code != ExitCode::Ok) return code;
        nlohmann::json sequence = nlohmann::json::array();
        StagedOutputs staged;
        HeldStdout held(stage);
        for (int f = 0; f < frames; ++f) {
            const Shown shown{frameFileName(output_, f, frames), plain.empty() ? plain : frameFileName(plain, f, frames)};
            options_.plainOutput = stage && !shown.plain.empty() ? staged.stage(shown.plain) : shown.plain;
            const std::string output = stage ? staged.stage(shown.output) : shown.output;
            const ExitCode code = packOne(inputs[f], output, shown, frames > 1 ? &sequence : nullptr);
            if (code != ExitCode::Ok) return code;
        }
        if (Status committed = staged.commit(); !committed) return fail(committed.error());
        held.release();
        if (frames > 1 && common_.json) printJson({{"command", "pack"}, {"frames", sequence}});
        if (frames > 1 && chatty()) printSequence();
        return ExitCode::Ok;
    }

private:
    // The names a report shows: the outputs as given, whatever staged name the job wrote to.
    struct Shown {
        std::string output, plain;
    };

    // What a sequence's summary line says of each frame.
    struct FrameText {
        std::string output, plain;
        std::string stored;  // "neighbour4 half, worst lookup error 0.0001 m"
        std::uintmax_t bytes = 0;
        double seconds = 0.0;
    };

    // One line for a whole sequence, as synth prints: the first and last outputs, what frame 0 was packed
    // from and as, and the totals; the pixel types, when --pixel-type auto chose differently per frame, each
    // with its frames' count.
    void printSequence() const {
        const FrameText& first = frames_.front();
        std::map<std::string, int> stored;
        std::uintmax_t bytes = 0;
        double seconds = 0.0;
        for (const FrameText& f : frames_) {
            ++stored[f.stored];
            bytes += f.bytes;
            seconds += f.seconds;
        }
        std::string storedText;
        for (const auto& [text, count] : stored)
            storedText += (storedText.empty() ? "" : "; ") + text +
                          (stored.size() > 1 ? " (" + std::to_string(count) + " frames)" : std::string());
        std::ostringstream line;
        line << "wrote " << first.output << " .. " << frames_.back().output << ": " << frames_.size() << " frames, "
             << firstFrame_ << storedText << ", " << compressionText() << ", " << humanBytes(bytes) << ", " << std::fixed
             << std::setprecision(2) << seconds << " s";
        std::cout << line.str() << "\n";
        std::cout << firstFrameNotes_;
        if (!first.plain.empty())
            std::cout << "wrote " << first.plain << " .. " << frames_.back().plain << ": unpacked chains\n";
    }

    // What the output holds: the EXR codec, or KTX2's supercompression (none for DDS).
    std::string compressionText() const {
        if (containerForPath(output_) == Container::Exr) return nameOf(options_.storage.exrCompression);
        return options_.storage.supercompression == Supercompression::Zstd ? "zstd" : "none";
    }

    // Packs one map; its JSON report goes to stdout, or into sequence when packing frames.
    ExitCode packOne(const std::string& input, const std::string& output, const Shown& shown, nlohmann::json* sequence) {
        Progress progress(!common_.quiet, "pack " + std::filesystem::path(input).filename().string(),
                          {{"load", 0.15}, {"mip", 0.35}, {"write", 0.5}});
        options_.progress = [&](std::string_view stage, double f) { progress.update(stage, f); };
        auto report = packHeightMap(input, output, options_);
        if (!report) {
            // An error names the file as the user gave it, not the staged temporary it is written to first.
            Error error = report.error();
            if (error.path == output) error.path = shown.output;
            if (!options_.plainOutput.empty() && error.path == options_.plainOutput) error.path = shown.plain;
            return fail(error);
        }
        progress.clear();
        std::error_code ec;
        const auto bytes = std::filesystem::file_size(report->output, ec);
        PackReport& r = *report;
        r.output = shown.output;
        if (!r.plainOutput.empty()) r.plainOutput = shown.plain;
        const int width = r.levelSizes[0].first, height = r.levelSizes[0].second;
        const double seconds = r.loadSeconds + r.mipSeconds + r.writeSeconds;
        const std::string compression = compressionText();

        const int channels = layoutChannels(r.layout);
        if (common_.json) {
            const nlohmann::json stored =
                storedChainJson(r.levelSizes, channels, r.pixelType, r.lookupError, options_.heightRange, "stored",
                                1 + (options_.shift ? 2 : 0) + (options_.foam ? 1 : 0));
            const nlohmann::json doc = {
                {"command", "pack"},
                {"input", r.input},
                {"output", r.output},
                {"plainOutput", r.plainOutput.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.plainOutput)},
                {"bytes", bytes},
                {"source", {{"format", r.source.format}, {"pixelType", r.source.pixelType},
                            {"width", r.source.width}, {"height", r.source.height},
                            {"channels", r.source.channels}, {"channelUsed", r.source.channelUsed},
                            {"channel", channelJson(r.source)},
                            {"decoder", r.source.decoder},
                            {"hash", r.sourceHash}}},
                {"resized", r.resized},
                {"resize", r.resized ? resizeJson(r.source.width, r.source.height, width, height) : nlohmann::json(nullptr)},
                {"layout", nameOf(r.layout)},
                {"displacement", !options_.shift ? nlohmann::json(nullptr)
                                 : r.layout == Layout::Neighbour4 ? nlohmann::json("neighbour4") : nlohmann::json("plain")},
                {"foam", !options_.foam ? nlohmann::json(nullptr)
                         : r.layout == Layout::Neighbour4 ? nlohmann::json("neighbour4") : nlohmann::json("plain")},
                {"wrap", nameOf(options_.mip.wrap)},
                {"filter", nameOf(options_.mip.filter)},
                {"compression", compression},
                {"pixelType", stored["pixelType"]},
                {"pixelTypeRequested", nameOf(pixelType_)},
                {"tolerance", options_.storage.tolerance > 0.0 ? nlohmann::json(tolerance_) : nlohmann::json(nullptr)},
                {"heightScale", options_.scale},
                {"heightOffset", options_.offset},
                {"heightRange", options_.heightRange > 0.0 ? nlohmann::json(options_.heightRange) : nlohmann::json(nullptr)},
                {"gpuBytes", stored["gpuBytes"]},
                {"lookupError", stored["lookupError"]},
                {"levels", stored["levels"]},
                {"timings", {{"load", r.loadSeconds}, {"mip", r.mipSeconds}, {"write", r.writeSeconds},
                             {"total", seconds}}},
            };
            if (sequence)
                sequence->push_back(doc);
            else
                printJson(doc);
        } else if (chatty()) {
            std::ostringstream what;  // the level sizes, the source, and how it was packed
            what << r.levelSizes[0].first << "x" << r.levelSizes[0].second << " (" << r.levelSizes.size()
                 << " levels) from " << r.source.width << "x" << r.source.height << " " << r.source.pixelType << " '"
                 << r.source.channelUsed << "'" << ", " << nameOf(options_.mip.wrap) << ", " << nameOf(options_.mip.filter)
                 << ", ";
            const std::string stored =
                std::string(nameOf(r.layout)) + " " + storedChainText(r.pixelType, r.lookupError, options_.heightRange);
            std::ostringstream notes;
            if (r.resized) notes << "  note: " << resizeNote(r.source.width, r.source.height, width, height) << "\n";
            if (!r.source.channelNote.empty()) notes << "  note: " << r.source.channelNote << "\n";
            const std::string plain = r.layout == Layout::Neighbour4 ? r.plainOutput : std::string();
            if (sequence) {  // one line for the sequence, once every frame is packed (printSequence)
                if (frames_.empty()) firstFrame_ = what.str(), firstFrameNotes_ = notes.str();
                frames_.push_back({r.output, plain, stored, bytes, seconds});
                return ExitCode::Ok;
            }
            std::ostringstream line;
            line << "wrote " << r.output << ": " << what.str() << stored << ", " << compression << ", " << humanBytes(bytes)
                 << ", " << std::fixed << std::setprecision(2) << seconds << " s";
            std::cout << line.str() << "\n" << notes.str();
            if (!plain.empty()) std::cout << "wrote " << plain << ": unpacked chain\n";
        }
        return ExitCode::Ok;
    }

    std::string input_, output_, channel_;
    PackOptions options_;
    std::string compression_ = nameOf(options_.storage.exrCompression), resize_ = "none";
    PixelTypeRequest pixelType_ = PixelTypeRequest::Float;
    std::string tolerance_;
    CLI::Option* compressionOption_ = nullptr;
    // A sequence's text: every frame's part, and frame 0's size, source and notes.
    std::vector<FrameText> frames_;
    std::string firstFrame_, firstFrameNotes_;
};

}  // namespace

std::unique_ptr<Command> makePackCommand() { return std::make_unique<PackCommand>(); }

}  // namespace heightpack::cli
