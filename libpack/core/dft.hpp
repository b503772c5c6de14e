// Internal: 2-D DFTs of double (and, for the sea's inverse, float) fields on all threads. OpenCV's cv::dft runs a 2-D transform on one thread;
// these run its 1-D row transforms in fixed blocks of rows, then of columns, each block on any thread, so
// the result does not depend on the thread count.
#pragma once

#include <opencv2/core.hpp>

#include <complex>
#include <functional>
#include <vector>

namespace heightpack::detail {

// The complex spectrum (CV_64FC2, h x w) of a real CV_64F field: cv::dft(field, out, DFT_COMPLEX_OUTPUT).
cv::Mat forwardDft(const cv::Mat& field, int threads);

// The real field (CV_64F) of a Hermitian spectrum, scaled by 1/(w h):
// cv::dft(spectrum, out, DFT_INVERSE | DFT_SCALE | DFT_REAL_OUTPUT). out may be a view of existing storage
// of that size and type (it is written in place).
void inverseDft(const cv::Mat& spectrum, cv::Mat& out, int threads);

// The half kx = 0 .. w/2 (rounded down) of the spectrum of a real w x h field, in floats: h rows of w/2 + 1
// complex values (as inverseRealDftOfHalf takes them), unscaled, as cv::dft with DFT_COMPLEX_OUTPUT gives
// them. give(y, row) writes the field's row y (w floats) into row, once per row, from any thread. Rows and
// then columns go in fixed blocks: the values do not depend on the thread count. A quarter of the work
// and memory of forwardDft, where a statistic or a model needs no more than float precision.
std::vector<std::complex<float>> forwardRealDftToHalf(int w, int h, int threads, const std::function<void(int y, float* row)>& give);

// The real w x h field of a Hermitian spectrum given by its half kx = 0 .. w/2 (rounded down): h rows of w/2 + 1
// complex floats (row r is ky = r, or r - h above h/2), unscaled (a plain sum over k, as cv::dft with
// DFT_INVERSE | DFT_REAL_OUTPUT and no DFT_SCALE). `half` is the scratch: it is overwritten. Each row of
// the field goes to take(y, row) once, from any thread, rows of one block in order; in float, rows and
// then columns split in fixed blocks, so the values do not depend on the thread count.
void inverseRealDftOfHalf(std::complex<float>* half, int w, int h, int threads,
                          const std::function<void(int y, const float* row)>& take);
// The rows go to take in blocks of this many (rows y with the same y / kInverseRowBlock), a block's rows in
// order and on one thread: a sum kept per block and added up in block order is the same on any thread count.
constexpr int kInverseRowBlock = 8;

// Several fields from one half spectrum S: field f is the real field of S(kx, ky) * factor[kx], a factor
// that depends on kx alone (i kx for d/dx, say), so one column pass serves them all and each costs only
// its row pass. factor holds w/2 + 1 values (empty: 1). At kx = 0 and w/2 the columns' value times the
// factor must be real, as it is when S times the factor is Hermitian (the field is real): only its real
// part is used there (w odd: at kx = 0 alone). Rows of a block come field by field, in the order given.
struct HalfSpectrumRows {
    std::vector<std::complex<float>> factor;
    std::function<void(int y, const float* row)> take;
};
void inverseRealDftOfHalf(std::complex<float>* half, int w, int h, int threads, const std::vector<HalfSpectrumRows>& fields);

// The same without a half spectrum of its own: give(q0, count, lines, lineStride) writes columns q0 ..
// q0 + count - 1 of the half spectrum to transform (w even: w/2 + 1 columns), every row r of column q0 + i
// at lines[i * lineStride + r], once per block of columns, from any thread; the column pass's result is
// kept in `scratch` for the row pass. Each block's rows are read from the scratch before any of them goes
// to a take, so a take may write over the scratch rows of its own block: the scratch can be the storage
// of the last field itself (the sea's heights in their interleaved image), and no spectrum-sized buffer
// is needed. The same values as the overload above given the same spectrum.
using HalfSpectrumSource = std::function<void(int q0, int count, std::complex<float>* lines, size_t lineStride)>;
struct HalfSpectrumScratch {
    float* first = nullptr;
    int stride = 1;
    std::complex<float>* lastColumn = nullptr;
};
void inverseRealDftOfHalf(int w, int h, int threads, const HalfSpectrumSource& give, const HalfSpectrumScratch& scratch,
                          const std::vector<HalfSpectrumRows>& fields);

}  // namespace heightpack::detail
