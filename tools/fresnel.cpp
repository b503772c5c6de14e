// heightpack fresnel: the 1D Fresnel / water-colour ramp a water shader indexes by N.V.
#include <iostream>
#include <sstream>

#include "heightpack/bake/fresnel_job.hpp"
#include "heightpack/version.hpp"

#include "command.hpp"
#include "enum_option.hpp"
#include "texture_options.hpp"

namespace heightpack::cli {

namespace {

class FresnelCommand final : public Command {
public:
    CLI::App* attach(CLI::App& app) override {
        CLI::App* cmd = app.add_subcommand("fresnel", "make a 1D Fresnel reflectance and water-colour ramp indexed by N.V");
        cmd->add_option("-o,--output", output_, "ramp to write: .exr, .ktx2, .dds (linear) or .png (8-bit, sRGB colours)")
            ->required();
        cmd->add_option("--ior", options_.ior, "index of refraction of the water (air is 1)")
            ->capture_default_str()
            ->check(finiteRange(1.0, 4.0));  // the manifest's range too (docs/manifest.md)
        addEnumOption(*cmd, "--model", options_.model, "exact: unpolarised Fresnel equations; schlick: Schlick's approximation");
        addEnumOption(*cmd, "--index", options_.index, "nv: u = N.V; 2nv: u = saturate(2 N.V), as the Isidoro shader indexes it");
        cmd->add_option("--deep", deep_, "linear colour seen looking straight down")
            ->capture_default_str()
            ->check(colourValidator());
        cmd->add_option("--shallow", shallow_, "linear colour seen at grazing angles")
            ->capture_default_str()
            ->check(colourValidator());
        cmd->add_option("--size", options_.size, "texels in the ramp")->capture_default_str()->check(CLI::Range(2, 65536));
        formatOption_ = addEnumOption(*cmd, "--format", format_, "exr or png8 (default: from the output's extension)")
                            ->default_str("");
        addPixelTypeOption(*cmd, pixelType_, false, nullptr, "",
                           {PixelTypeRequest::Float, PixelTypeRequest::Half, PixelTypeRequest::Uint16});
        addCommonOptions(*cmd);
        cmd->footer(
            "Examples:\n"
            "  heightpack fresnel --ior 1.333 --deep " + deep_ + " --shallow " + shallow_ + " --size 256 -o out/fresnel.exr\n"
            "  heightpack fresnel --ior 1.333 --model schlick --format png8 -o fresnel.png\n"
            "  heightpack fresnel --pixel-type half -o fresnel.dds\n"
            "Texel i stands for N.V = (i + 0.5) / size (half that with --index 2nv); rgb = mix(shallow, deep, N.V),\n"
            "alpha = the reflectance F, so a shader does mix(rgb, reflection, F) with one fetch.\n");
        return cmd;
    }

    ExitCode run() override {
        if (const ExitCode code = checkOutputs({}, {{output_, "-o", {".exr", ".ktx2", ".dds", ".png"}}});
            code != ExitCode::Ok)
            return code;
        const std::optional<RampFormat> format =
            outputFormat(formatOption_->count() > 0 ? std::optional(format_) : std::nullopt, output_);
        if (!format) return usage("the output must end in .exr, .ktx2, .dds or .png, matching --format if given");
        const PixelType pixelType = requestedPixelType(pixelType_);
        if (format == RampFormat::Png8 && pixelType != PixelType::Float)
            return usage("--pixel-type is for .exr, .ktx2 and .dds outputs; a PNG ramp is 8-bit");
        Supercompression none;
        if (const std::string problem = checkContainerChoice({output_}, pixelType, std::nullopt, none); !problem.empty())
            return usage(problem);
        options_.deep = *parseColour(deep_);
        options_.shallow = *parseColour(shallow_);
        const Status written = writeFresnelRamp(output_, options_, *format,
                                                kVersion, pixelType);
        if (!written) return fail(written.error());
        const double f0 = fresnelReflectance(1.0, options_.ior, options_.model);
        if (common_.json) {
            printJson({{"command", "fresnel"}, {"output", output_}, {"format", formatWord(*format, output_)}, {"ior", options_.ior},
                       {"model", nameOf(options_.model)}, {"index", nameOf(options_.index)}, {"size", options_.size}, {"deep", options_.deep},
                       {"shallow", options_.shallow}, {"reflectanceAtNormalIncidence", f0}});
        } else if (chatty()) {
            std::ostringstream line;
            line << "wrote " << output_ << ": " << options_.size << "x1 " << formatWord(*format, output_) << ", ior " << options_.ior << ", "
                 << nameOf(options_.model) << ", index " << nameOf(options_.index) << ", F(0 deg) = " << std::setprecision(4) << f0;
            std::cout << line.str() << "\n";
        }
        return ExitCode::Ok;
    }

private:
    std::string output_;
    RampFormat format_ = RampFormat::Exr;
    CLI::Option* formatOption_ = nullptr;
    PixelTypeRequest pixelType_ = PixelTypeRequest::Float;
    FresnelOptions options_;
    std::string deep_ = colourText(options_.deep), shallow_ = colourText(options_.shallow);
};

}  // namespace

std::unique_ptr<Command> makeFresnelCommand() { return std::make_unique<FresnelCommand>(); }

}  // namespace heightpack::cli
