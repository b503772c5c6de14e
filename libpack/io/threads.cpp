#include "heightpack/io/threads.hpp"

#include <OpenEXR/ImfThreading.h>

#include "heightpack/core/parallel.hpp"

#include "format_module_loader.hpp"

namespace heightpack {

void setLibraryThreads(int threads) {
    const int n = resolveThreadCount(threads);
    detail::setFormatModuleThreads(n);  // OpenImageIO's pool, should its module load
    // OpenEXR compresses tiles on its own pool; with one thread it does the work inline.
    Imf::setGlobalThreadCount(n > 1 ? n : 0);
}

}  // namespace heightpack
