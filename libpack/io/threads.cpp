#include "heightpack/io/threads.hpp"

#include <OpenEXR/ImfThreading.h>
#include <OpenImageIO/imageio.h>

#include "heightpack/core/parallel.hpp"

namespace heightpack {

void setLibraryThreads(int threads) {
    const int n = resolveThreadCount(threads);
    OIIO::attribute("threads", n);
    // OpenEXR compresses tiles on its own pool; with one thread it does the work inline.
    Imf::setGlobalThreadCount(n > 1 ? n : 0);
}

}  // namespace heightpack
