#include "dft.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <numbers>
#include <type_traits>
#include <vector>

#include "heightpack/core/parallel.hpp"

namespace heightpack::detail {

namespace {

// Lines per task: a column block is gathered into a small row-major matrix, so 16 columns (256 bytes of
// complex doubles, 128 of complex floats, per row) are read and written a cache line at a time.
constexpr int kBlock = 16;
// The sea's float transforms: 8 complex floats, one cache line, a row. As fast as 16 (117 against 125 ms
// for a 4096^2 field on one core) with half the buffers a thread, which synth's peak memory counts.
constexpr int kFloatBlock = kInverseRowBlock;

// The 1-D complex transform of every column of in (CV_64FC2 with Vec2d, CV_32FC2 with Vec2f), with the
// row flags given, into out (of in's size and type; may be in).
template <typename Complex>
void transformColumns(const cv::Mat& in, cv::Mat& out, int flags, int threads) {
    const int h = in.rows, w = in.cols;
    constexpr int size = std::is_same_v<Complex, cv::Vec2f> ? kFloatBlock : kBlock;
    parallelFor((w + size - 1) / size, threads, [&](int begin, int end) {
        // Rows padded by a cache line: h values apart (a power of two), the rows a gathered line is
        // written across all fell into the same cache sets and evicted each other.
        cv::Mat padded(size, h + int(64 / sizeof(Complex)), in.type());
        cv::Mat lines = padded.colRange(0, h);
        for (int block = begin; block < end; ++block) {
            const int x0 = block * size, count = std::min(size, w - x0);
            cv::Mat gathered = lines.rowRange(0, count);
            for (int y = 0; y < h; ++y) {
                const Complex* row = in.ptr<Complex>(y) + x0;
                for (int i = 0; i < count; ++i) gathered.ptr<Complex>(i)[y] = row[i];
            }
            cv::dft(gathered, gathered, flags | cv::DFT_ROWS);
            for (int y = 0; y < h; ++y) {
                Complex* row = out.ptr<Complex>(y) + x0;
                for (int i = 0; i < count; ++i) row[i] = gathered.ptr<Complex>(i)[y];
            }
        }
    });
}

// The rows of in, transformed with flags in blocks, written to out (already of the result's size and type).
void transformRows(const cv::Mat& in, cv::Mat& out, int flags, int threads) {
    parallelFor((in.rows + kBlock - 1) / kBlock, threads, [&](int begin, int end) {
        for (int block = begin; block < end; ++block) {
            const int y0 = block * kBlock, y1 = std::min(in.rows, y0 + kBlock);
            cv::Mat target = out.rowRange(y0, y1);
            cv::dft(in.rowRange(y0, y1), target, flags | cv::DFT_ROWS);
        }
    });
}

// The row pass of an inverse real DFT: the half spectrum's rows, once through the column pass, as
// row(y, buffer) gives them (a pointer to w/2 + 1 complex values, in buffer or elsewhere), times each
// field's factor and transformed to real rows in blocks; a block's rows are all got before any goes to a take.
// Column 0 and (w even) column w/2 are real by then (each is the transform of a Hermitian column), so a row
// is OpenCV's packed real spectrum (CCS) Re0, Re1, Im1, ..., Re(w/2 - 1), Im(w/2 - 1), Re(w/2) (w odd:
// Re0, Re1, Im1, ..., Re(w/2), Im(w/2)): w floats, copied (times each field's factor) into a block of
// rows and transformed to real rows together. Every field's rows come from the one column pass.
template <typename RowOf>
void rowPass(int w, int h, int threads, const std::vector<HalfSpectrumRows>& fields, const RowOf& rowOf) {
    const bool even = w % 2 == 0;  // an even row has a real last column (w/2), an odd one none
    const int columns = w / 2 + 1;
    for (const HalfSpectrumRows& field : fields) CV_Assert(field.factor.empty() || int(field.factor.size()) == columns);
    parallelFor((h + kFloatBlock - 1) / kFloatBlock, threads, [&](int begin, int end) {
        cv::Mat packed(kFloatBlock, w, CV_32F), real(kFloatBlock, w, CV_32F);
        std::vector<std::complex<float>> buffer(size_t(kFloatBlock) * columns);
        const std::complex<float>* rows[kFloatBlock];
        for (int block = begin; block < end; ++block) {
            const int y0 = block * kFloatBlock, count = std::min(kFloatBlock, h - y0);
            for (int i = 0; i < count; ++i) rows[i] = rowOf(y0 + i, buffer.data() + size_t(i) * columns);
            for (const HalfSpectrumRows& field : fields) {
                for (int i = 0; i < count; ++i) {
                    const std::complex<float>* from = rows[i];
                    float* to = packed.ptr<float>(i);
                    if (field.factor.empty()) {
                        const float* values = reinterpret_cast<const float*>(from);
                        to[0] = values[0];
                        std::copy(values + 2, values + w + (even ? 0 : 1), to + 1);
                        if (even) to[w - 1] = values[w];
                        continue;
                    }
                    const std::complex<float>* factor = field.factor.data();
                    to[0] = (from[0] * factor[0]).real();
                    for (int q = 1; q < (even ? w / 2 : columns); ++q) {
                        const std::complex<float> z = from[q] * factor[q];
                        to[2 * q - 1] = z.real();
                        to[2 * q] = z.imag();
                    }
                    if (even) to[w - 1] = (from[w / 2] * factor[w / 2]).real();
                }
                cv::Mat out = real.rowRange(0, count);
                cv::dft(packed.rowRange(0, count), out, cv::DFT_INVERSE | cv::DFT_ROWS | cv::DFT_REAL_OUTPUT);
                for (int i = 0; i < count; ++i) field.take(y0 + i, out.ptr<float>(i));
            }
        }
    });
}

// inverseRealDftOfHalf through a scratch of floats `Stride` apart (0: scratch.stride, known at run time only).
template <int Stride>
void inverseThroughScratch(int w, int h, int threads, const HalfSpectrumSource& give, const HalfSpectrumScratch& scratch,
                           const std::vector<HalfSpectrumRows>& fields) {
    const int columns = w / 2 + 1, half = w / 2;
    const size_t stride = Stride > 0 ? size_t(Stride) : size_t(scratch.stride);
    // Float j of row y (j < w: complex j / 2's real part, or imaginary) in scratch.first; complex w/2 of row
    // y in lastColumn[y].
    auto row = [&](int y) { return scratch.first + size_t(y) * w * stride; };
    // The column pass, as transformColumns's: a block of columns gathered (from give) into lines, each line
    // transformed, the result put back into the scratch.
    parallelFor((columns + kFloatBlock - 1) / kFloatBlock, threads, [&](int begin, int end) {
        cv::Mat padded(kFloatBlock, h + int(64 / sizeof(cv::Vec2f)), CV_32FC2);
        cv::Mat lines = padded.colRange(0, h);
        const size_t lineStride = padded.step1() / 2;  // complex values from one line to the next
        for (int block = begin; block < end; ++block) {
            const int x0 = block * kFloatBlock, count = std::min(kFloatBlock, columns - x0);
            const int inside = std::min(count, half - x0);  // the block's columns below w/2
            cv::Mat gathered = lines.rowRange(0, count);
            const cv::Vec2f* first = gathered.ptr<cv::Vec2f>(0);
            give(x0, count, reinterpret_cast<std::complex<float>*>(gathered.ptr<cv::Vec2f>(0)), lineStride);
            cv::dft(gathered, gathered, cv::DFT_INVERSE | cv::DFT_ROWS);
            for (int y = 0; y < h; ++y) {
                float* to = row(y) + 2 * size_t(x0) * stride;
                for (int i = 0; i < inside; ++i) {
                    const cv::Vec2f z = first[i * lineStride + y];
                    to[2 * i * stride] = z[0], to[(2 * i + 1) * stride] = z[1];
                }
                if (inside < count) scratch.lastColumn[y] = {first[inside * lineStride + y][0], first[inside * lineStride + y][1]};
            }
        }
    });
    // Each row copied out of the scratch before its block's rows go to any take: a take may write over
    // the scratch rows of its own block (the sea's heights are written where their spectrum was).
    rowPass(w, h, threads, fields, [&](int y, std::complex<float>* out) -> const std::complex<float>* {
        const float* from = row(y);
        float* to = reinterpret_cast<float*>(out);
        for (int j = 0; j < w; ++j) to[j] = from[j * stride];
        out[half] = scratch.lastColumn[y];
        return out;
    });
}

}  // namespace

cv::Mat forwardDft(const cv::Mat& field, int threads) {
    CV_Assert(field.type() == CV_64F);
    cv::Mat spectrum(field.rows, field.cols, CV_64FC2);
    transformRows(field, spectrum, cv::DFT_COMPLEX_OUTPUT, threads);
    transformColumns<cv::Vec2d>(spectrum, spectrum, 0, threads);
    return spectrum;
}

void inverseDft(const cv::Mat& spectrum, cv::Mat& out, int threads) {
    CV_Assert(spectrum.type() == CV_64FC2);
    cv::Mat columns(spectrum.rows, spectrum.cols, CV_64FC2);
    transformColumns<cv::Vec2d>(spectrum, columns, cv::DFT_INVERSE | cv::DFT_SCALE, threads);
    out.create(spectrum.rows, spectrum.cols, CV_64F);
    transformRows(columns, out, cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_REAL_OUTPUT, threads);
}

std::vector<std::complex<float>> forwardRealDftToHalf(int w, int h, int threads, const std::function<void(int y, float* row)>& give) {
    CV_Assert(w >= 1 && h >= 1);
    const int columns = w / 2 + 1;
    std::vector<std::complex<float>> half(size_t(h) * columns);
    parallelFor((h + kFloatBlock - 1) / kFloatBlock, threads, [&](int begin, int end) {
        cv::Mat rows(kFloatBlock, w, CV_32F), spectra;
        for (int block = begin; block < end; ++block) {
            const int y0 = block * kFloatBlock, count = std::min(kFloatBlock, h - y0);
            for (int i = 0; i < count; ++i) give(y0 + i, rows.ptr<float>(i));
            cv::dft(rows.rowRange(0, count), spectra, cv::DFT_ROWS | cv::DFT_COMPLEX_OUTPUT);
            for (int i = 0; i < count; ++i) {
                const cv::Vec2f* from = spectra.ptr<cv::Vec2f>(i);
                for (int q = 0; q < columns; ++q) half[size_t(y0 + i) * columns + q] = {from[q][0], from[q][1]};
            }
        }
    });
    cv::Mat spectrum(h, columns, CV_32FC2, half.data());
    transformColumns<cv::Vec2f>(spectrum, spectrum, 0, threads);
    return half;
}

void inverseRealDftOfHalf(std::complex<float>* half, int w, int h, int threads,
                          const std::function<void(int y, const float* row)>& take) {
    inverseRealDftOfHalf(half, w, h, threads, {HalfSpectrumRows{{}, take}});
}

void inverseRealDftOfHalf(std::complex<float>* half, int w, int h, int threads, const std::vector<HalfSpectrumRows>& fields) {
    CV_Assert(w >= 2 && h >= 1);
    cv::Mat spectrum(h, w / 2 + 1, CV_32FC2, half);
    transformColumns<cv::Vec2f>(spectrum, spectrum, cv::DFT_INVERSE, threads);
    // The columns' result is only read from here on: a row is handed over where it lies.
    rowPass(w, h, threads, fields, [&](int y, std::complex<float>*) -> const std::complex<float>* {
        return reinterpret_cast<const std::complex<float>*>(spectrum.ptr<cv::Vec2f>(y));
    });
}

void inverseRealDftOfHalf(int w, int h, int threads, const HalfSpectrumSource& give, const HalfSpectrumScratch& scratch,
                          const std::vector<HalfSpectrumRows>& fields) {
    CV_Assert(w >= 2 && w % 2 == 0 && h >= 1 && scratch.first && scratch.stride >= 1 && scratch.lastColumn);
    // A plane (stride 1) and an interleaved image of four channels (synth's) get their own copy loops, the
    // stride known to the compiler so that they vectorise.
    if (scratch.stride == 1) return inverseThroughScratch<1>(w, h, threads, give, scratch, fields);
    if (scratch.stride == 4) return inverseThroughScratch<4>(w, h, threads, give, scratch, fields);
    inverseThroughScratch<0>(w, h, threads, give, scratch, fields);
}

}  // namespace heightpack::detail
