#include "level_write.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>

#include "heightpack/core/parallel.hpp"
#include "heightpack/io/files.hpp"

namespace heightpack::detail {

namespace {

// Bytes a band holds at most: small enough to stay in a core's cache between being encoded and being
// copied into the page cache, large enough that a system call a band costs nothing.
constexpr size_t kBandBytes = size_t(1) << 20;

struct Band {
    int layer = 0, level = 0, y0 = 0, rows = 0;
    std::uint64_t offset = 0;
};

bool writeAllAt(int fd, const std::uint8_t* data, size_t n, std::uint64_t offset) {
    while (n > 0) {
        const ssize_t done = ::pwrite(fd, data, n, static_cast<off_t>(offset));
        if (done < 0 && errno == EINTR) continue;
        if (done <= 0) return false;
        data += done;
        n -= size_t(done);
        offset += std::uint64_t(done);
    }
    return true;
}

Error cannotWriteBecause(const std::string& path, const char* step) {
    return cannotWrite(path, std::string(step) + " failed", "check free disk space and permissions");
}

// The file's bands in file order; the zeros before any image that does not start where the one before
// ended (alignment) are written here, as they are few.
Status planBands(const std::string& path, int fd, const std::vector<std::uint8_t>& header,
                 const std::vector<PlacedImage>& images, const ChainToWrite& content, const EncodePlan& plan,
                 std::vector<Band>& bands, long long& rowsTotal) {
    if (!writeAllAt(fd, header.data(), header.size(), 0)) return cannotWriteBecause(path, "writing the header");
    const size_t texelBytes = size_t(plan.format.bytesPerTexel());
    std::uint64_t end = header.size();
    for (const PlacedImage& image : images) {
        const int w = mipLevelSide(content.width, image.level), h = mipLevelSide(content.height, image.level);
        if (image.offset < end)
            return Error{ErrorKind::Internal, path, "internal error: a level overlaps what comes before it",
                         "please report this"};
        if (image.offset > end) {
            const std::vector<std::uint8_t> zeros(image.offset - end, 0);
            if (!writeAllAt(fd, zeros.data(), zeros.size(), end)) return cannotWriteBecause(path, "writing padding");
        }
        const size_t rowBytes = size_t(w) * texelBytes;
        // A band's rows are filled as floats first (but for float texels, filled in place): the larger
        // of the two sizes a band.
        const size_t filledBytes = std::max(rowBytes, size_t(w) * size_t(plan.sourceChannels) * sizeof(float));
        const int bandRows = int(std::clamp<size_t>(kBandBytes / filledBytes, 1, size_t(h)));
        for (int y0 = 0; y0 < h; y0 += bandRows)
            bands.push_back({image.layer, image.level, y0, std::min(bandRows, h - y0),
                             image.offset + std::uint64_t(y0) * rowBytes});
        end = image.offset + std::uint64_t(h) * rowBytes;
        rowsTotal += h;
    }
    return Done{};
}

Status writeBands(const std::string& path, int fd, EarlyWriteback& writeback, const std::vector<Band>& bands,
                  long long rowsTotal, const ChainToWrite& content, const EncodePlan& plan, int threads,
                  const std::function<void(double)>& progress) {
    // Worker k takes bands k, k + workers, ...: the threads move through the file side by side. A band
    // that fails is recorded and the others still encoded (not written), so the error reported is the
    // first in file order whatever the thread count.
    const int workers = std::min(resolveThreadCount(threads), int(std::max<size_t>(bands.size(), 1)));
    std::vector<Status> encoded(bands.size(), Done{});
    std::atomic<bool> anyFailed{false}, writeFailed{false};
    std::atomic<long long> rowsDone{0};
    parallelFor(workers, workers, [&](int first, int last) {
        for (int worker = first; worker < last; ++worker) {
            BandEncoder encoder(path, content, plan, 1);
            for (size_t b = size_t(worker); b < bands.size(); b += size_t(workers)) {
                const Band& band = bands[b];
                encoded[b] = encoder.encode(band.level, band.y0, band.rows, band.layer);
                if (!encoded[b]) anyFailed = true;
                if (anyFailed) continue;
                const std::vector<std::uint8_t>& bytes = encoder.bytes();
                if (!writeAllAt(fd, bytes.data(), bytes.size(), band.offset)) {
                    writeFailed = anyFailed = true;
                    continue;
                }
                writeback.wrote(bytes.size());
                const long long done = rowsDone += band.rows;
                // parallelFor runs worker 0 on the calling thread: the only one that reports.
                if (worker == 0 && progress) progress(double(done) / double(rowsTotal));
            }
        }
    });
    for (const Status& s : encoded)
        if (!s) return s;
    if (writeFailed) return cannotWriteBecause(path, "writing a level");
    if (progress) progress(1.0);
    return Done{};
}

}  // namespace

Status writePlacedImages(const std::string& path, const std::string& temporaryPath, const std::vector<std::uint8_t>& header,
                         const std::vector<PlacedImage>& images, const ChainToWrite& content, const EncodePlan& plan,
                         int threads, const std::function<void(double)>& progress) {
    const int fd = ::open(temporaryPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) return cannotWriteBecause(path, "creating the file");
    std::vector<Band> bands;
    long long rowsTotal = 0;
    Status written = planBands(path, fd, header, images, content, plan, bands, rowsTotal);
    if (written) {
        EarlyWriteback writeback(temporaryPath);
        written = writeBands(path, fd, writeback, bands, rowsTotal, content, plan, threads, progress);
    }
    if (::close(fd) != 0 && written) return cannotWriteBecause(path, "closing the file");
    return written;
}

}  // namespace heightpack::detail
