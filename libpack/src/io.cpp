#include "heightpack/io.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfTiledOutputFile.h>
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <xxhash.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "stderr_silencer.hpp"

namespace heightpack {

namespace fs = std::filesystem;

namespace {

std::string firstLine(std::string text) {
    const auto end = text.find('\n');
    if (end != std::string::npos) text.resize(end);
    while (!text.empty() && (text.back() == ' ' || text.back() == '.')) text.pop_back();
    return text;
}

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string sizeText(long long w, long long h) { return std::to_string(w) + "x" + std::to_string(h); }

// Finds the channel that --channel names: by name first (R, red, ...), then by position.
int findChannel(const OIIO::ImageSpec& spec, ChannelSelect select) {
    static const char* names[][2] = {{"r", "red"}, {"g", "green"}, {"b", "blue"}, {"a", "alpha"}};
    const int which = select == ChannelSelect::R ? 0 : select == ChannelSelect::G ? 1 : select == ChannelSelect::B ? 2 : 3;
    for (int c = 0; c < spec.nchannels; ++c) {
        const std::string n = lower(spec.channelnames[c]);
        if (n == names[which][0] || n == names[which][1]) return c;
    }
    if (which == 3) return spec.alpha_channel;
    return which < spec.nchannels && which != spec.alpha_channel ? which : -1;
}

}  // namespace

std::optional<ChannelSelect> parseChannelSelect(std::string_view name) {
    if (name == "r") return ChannelSelect::R;
    if (name == "g") return ChannelSelect::G;
    if (name == "b") return ChannelSelect::B;
    if (name == "a") return ChannelSelect::A;
    if (name == "luma") return ChannelSelect::Luma;
    return std::nullopt;
}

Result<LoadedHeights> loadHeightMap(const std::string& path, const LoadOptions& options) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) return badInput(path, "no such file", "check the path");
    if (fs::is_directory(status)) return badInput(path, "is a folder, not an image", "name an image file");
    if (fs::file_size(path, ec) == 0) return badInput(path, "file is empty", "export the height map again");

    // Keep colour and alpha as stored: an RGBA height map's channels are data, not premultiplied colour.
    detail::StderrSilencer quiet(options.silenceDecoderMessages);
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) {
        return badInput(path, "cannot be read as an image: " + firstLine(OIIO::geterror()),
                        "export it as PNG, TIFF or EXR");
    }
    const OIIO::ImageSpec spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.depth > 1 || spec.nchannels <= 0)
        return badInput(path, "has no 2D pixel data", "export it as a flat 2D image");
    if (spec.width > options.maxSide || spec.height > options.maxSide ||
        int64_t(spec.width) * spec.height > options.maxTexels) {
        return badInput(path, "is " + sizeText(spec.width, spec.height) + ", larger than heightpack accepts (" +
                                  std::to_string(options.maxSide) + " texels a side, " +
                                  std::to_string(options.maxTexels) + " texels in all)",
                        "split or downsize the map");
    }

    LoadedHeights out;
    SourceInfo& src = out.source;
    src.path = path;
    src.format = in->format_name();
    src.pixelType = spec.format.c_str();
    src.width = spec.width;
    src.height = spec.height;
    src.channels = spec.nchannels;

    const int colourChannels = spec.nchannels - (spec.alpha_channel >= 0 ? 1 : 0);
    const bool colour = colourChannels > 1;
    int channel = 0;
    bool luma = false;
    switch (options.channel) {
        case ChannelSelect::Auto:
            if (colour) {
                return badInput(path,
                                "is a colour image with " + std::to_string(spec.nchannels) + " channels",
                                "choose the height channel with --channel r|g|b|a|luma");
            }
            channel = spec.alpha_channel == 0 && spec.nchannels > 1 ? 1 : 0;
            break;
        case ChannelSelect::Luma:
            luma = colour && colourChannels >= 3;
            channel = spec.alpha_channel == 0 && spec.nchannels > 1 ? 1 : 0;
            break;
        default:
            // A grey image is its own red, green and blue.
            channel = colour || options.channel == ChannelSelect::A ? findChannel(spec, options.channel)
                                                                      : (spec.alpha_channel == 0 ? 1 : 0);
            if (channel < 0) {
                return badInput(path, "has no such channel (it has " + std::to_string(spec.nchannels) + ")",
                                "pick one it has with --channel");
            }
    }
    src.channelUsed = luma ? "luma" : spec.channelnames[channel];

    const int chBegin = luma ? 0 : channel;
    const int chCount = luma ? 3 : 1;
    std::vector<float> pixels;
    try {
        pixels.resize(spec.image_pixels() * chCount);
    } catch (const std::bad_alloc&) {
        return badInput(path, "is " + sizeText(spec.width, spec.height) + ", too large for this machine's memory",
                        "split or downsize the map");
    }
    if (!in->read_image(0, 0, chBegin, chBegin + chCount, OIIO::TypeDesc::FLOAT, pixels.data())) {
        return badInput(path, "is damaged or truncated: " + firstLine(in->geterror()),
                        "export the height map again");
    }
    in->close();

    Image& heights = out.heights;
    heights = Image(spec.width, spec.height, 1);
    if (luma) {
        // Rec. 709 weights on the stored values: heights are data, so no transfer curve is undone.
        for (size_t i = 0; i < heights.pixels.size(); ++i)
            heights.pixels[i] = 0.2126f * pixels[3 * i] + 0.7152f * pixels[3 * i + 1] + 0.0722f * pixels[3 * i + 2];
    } else {
        heights.pixels = std::move(pixels);
    }
    for (size_t i = 0; i < heights.pixels.size(); ++i) {
        if (!std::isfinite(heights.pixels[i])) {
            const size_t x = i % spec.width, y = i / spec.width;
            return badInput(path,
                            std::string("holds ") + (std::isnan(heights.pixels[i]) ? "NaN" : "an infinite value") +
                                " at texel " + std::to_string(x) + "," + std::to_string(y),
                            "fix the map in the tool that made it");
        }
    }
    return out;
}

std::string hashPixels(const Image& image) {
    const XXH64_hash_t h = XXH3_64bits(image.pixels.data(), image.pixels.size() * sizeof(float));
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
    return text;
}

const char* compressionName(Compression compression) {
    switch (compression) {
        case Compression::None: return "none";
        case Compression::Rle: return "rle";
        case Compression::Zips: return "zips";
        case Compression::Zip: return "zip";
        case Compression::Piz: return "piz";
    }
    return "?";
}

std::optional<Compression> parseCompression(std::string_view name) {
    for (Compression c : {Compression::None, Compression::Rle, Compression::Zips, Compression::Zip, Compression::Piz})
        if (name == compressionName(c)) return c;
    return std::nullopt;
}

// ---- Atomic output ------------------------------------------------------------------------------

namespace {

// Paths of temporary files being written, kept in plain arrays so a signal handler can unlink them
// without allocating or locking.
constexpr int kMaxPending = 32;
constexpr size_t kMaxPath = 4096;
char pendingPath[kMaxPending][kMaxPath];
std::atomic<bool> pendingUsed[kMaxPending];
std::mutex pendingMutex;

// A temporary file beside the final output; renamed over it by commit(), removed otherwise.
class TemporaryFile {
public:
    explicit TemporaryFile(const std::string& finalPath) : finalPath_(finalPath) {
        static std::atomic<unsigned> counter{0};
        const fs::path target(finalPath);
        // Keep the extension last: libraries that choose a format by file name must still see it.
        // Built with append: GCC 12 gives a false -Wrestrict on a chain of operator+ here.
        std::string name = ".";
        name.append(target.stem().string()).append(".hptmp-").append(std::to_string(::getpid()));
        name.append("-").append(std::to_string(counter++)).append(target.extension().string());
        path_ = (target.parent_path() / name).string();
        std::lock_guard<std::mutex> lock(pendingMutex);
        for (int i = 0; i < kMaxPending && path_.size() < kMaxPath; ++i) {
            if (!pendingUsed[i].load()) {
                std::memcpy(pendingPath[i], path_.c_str(), path_.size() + 1);
                pendingUsed[i].store(true);
                slot_ = i;
                break;
            }
        }
    }
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;
    ~TemporaryFile() {
        if (!committed_) ::unlink(path_.c_str());
        if (slot_ >= 0) pendingUsed[slot_].store(false);
    }

    const std::string& path() const { return path_; }

    Status commit() {
        // Keep the permissions a replaced file had (the temporary file gets the default mode).
        struct stat st {};
        if (::stat(finalPath_.c_str(), &st) == 0) ::chmod(path_.c_str(), st.st_mode & 07777);
        if (::rename(path_.c_str(), finalPath_.c_str()) != 0)
            return cannotWrite(finalPath_, std::string("cannot move the finished file into place: ") + std::strerror(errno),
                               "check the folder's permissions");
        committed_ = true;
        return Done{};
    }

private:
    std::string finalPath_;
    std::string path_;
    int slot_ = -1;
    bool committed_ = false;
};

Imf::Compression toImf(Compression compression) {
    switch (compression) {
        case Compression::None: return Imf::NO_COMPRESSION;
        case Compression::Rle: return Imf::RLE_COMPRESSION;
        case Compression::Zips: return Imf::ZIPS_COMPRESSION;
        case Compression::Zip: return Imf::ZIP_COMPRESSION;
        case Compression::Piz: return Imf::PIZ_COMPRESSION;
    }
    return Imf::ZIP_COMPRESSION;
}

}  // namespace

void removePendingTemporaryFiles() {
    for (int i = 0; i < kMaxPending; ++i)
        if (pendingUsed[i].load()) ::unlink(pendingPath[i]);
}

Status checkWritable(const std::string& path) {
    std::error_code ec;
    const fs::path target(path);
    if (target.filename().empty()) return cannotWrite(path, "names a folder, not a file", "give an output file name");
    const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    if (!fs::exists(folder, ec))
        return cannotWrite(path, "folder " + folder.string() + " does not exist", "create it first");
    if (!fs::is_directory(folder, ec))
        return cannotWrite(path, folder.string() + " is not a folder", "choose another output path");
    if (::access(folder.c_str(), W_OK) != 0)
        return cannotWrite(path, "folder " + folder.string() + " is not writable", "choose another output folder");
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) {
        if (S_ISDIR(st.st_mode)) return cannotWrite(path, "is a folder", "give an output file name");
        // Checked by mode bits too: root passes access(W_OK) on any file, but a read-only output was
        // made read-only on purpose.
        if ((st.st_mode & 0222) == 0 || ::access(path.c_str(), W_OK) != 0)
            return cannotWrite(path, "exists and is read-only", "make it writable or choose another output");
    }
    return Done{};
}

Status writeTiledExr(const std::string& path, const TiledExrContent& content, const ExrWriteOptions& options) {
    assert(content.width > 0 && content.height > 0 && !content.channelNames.empty() && content.fillRows);
    if (Status writable = checkWritable(path); !writable) return writable;

    Imf::Header header(content.width, content.height);
    header.compression() = toImf(options.compression);
    header.setTileDescription(
        Imf::TileDescription(options.tileSize, options.tileSize, Imf::MIPMAP_LEVELS, Imf::ROUND_DOWN));
    for (const std::string& name : content.channelNames) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    for (const ExrAttribute& a : content.attributes) {
        if (const auto* s = std::get_if<std::string>(&a.value))
            header.insert(a.name, Imf::StringAttribute(*s));
        else
            header.insert(a.name, Imf::FloatAttribute(std::get<float>(a.value)));
    }

    TemporaryFile temp(path);
    try {
        Imf::TiledOutputFile file(temp.path().c_str(), header);
        const int channels = static_cast<int>(content.channelNames.size());
        const size_t texelBytes = sizeof(float) * channels;
        long long rowsTotal = 0, rowsDone = 0;
        for (int level = 0; level < file.numLevels(); ++level) rowsTotal += file.levelHeight(level);
        std::vector<float> band;
        for (int level = 0; level < file.numLevels(); ++level) {
            const int w = file.levelWidth(level), h = file.levelHeight(level);
            band.resize(static_cast<size_t>(w) * options.tileSize * channels);
            for (int ty = 0; ty < file.numYTiles(level); ++ty) {
                const int y0 = ty * options.tileSize;
                const int rows = std::min(options.tileSize, h - y0);
                content.fillRows(level, y0, rows, band.data());
                Imf::FrameBuffer frame;
                for (int c = 0; c < channels; ++c) {
                    frame.insert(content.channelNames[c],
                                 Imf::Slice::Make(Imf::FLOAT, band.data() + c, IMATH_NAMESPACE::V2i(0, y0), w, rows,
                                                  texelBytes, texelBytes * w));
                }
                file.setFrameBuffer(frame);
                // A whole row of tiles per call lets OpenEXR compress them in parallel.
                file.writeTiles(0, file.numXTiles(level) - 1, ty, ty, level);
                rowsDone += rows;
                if (options.progress) options.progress(double(rowsDone) / rowsTotal);
            }
        }
    } catch (const std::exception& e) {
        return cannotWrite(path, "writing failed: " + firstLine(e.what()), "check free disk space and permissions");
    }
    return temp.commit();
}

}  // namespace heightpack
