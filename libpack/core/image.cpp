#include "heightpack/core/image.hpp"

namespace heightpack {

const char* wrapName(Wrap wrap) { return wrap == Wrap::Periodic ? "periodic" : "clamp"; }

}  // namespace heightpack
