// Decoders of block-compressed texels that are not heightpack's: the Khronos Data Format Specification's
// RGTC table written out here, and ARM's astcenc command line. The block format tests judge heightpack's
// encoder by them, never by its own decoder alone.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "heightpack/core/image.hpp"
#include "support/test_support.hpp"

namespace heightpack::test {

// The bytes a hex string (two digits a byte, as read_container.mjs prints blocks) spells.
std::vector<unsigned char> hexBytes(const std::string& hex);
// "1.5,0.25,..." as numbers (a recorded per-level attribute).
std::vector<double> numberList(const std::string& text);

// RGTC blocks (BC4: channels 1, BC5: 2) decoded as the specification's table says, in double precision:
// channel c of texel (x, y) as a code value 0..255.
Image rgtcDecode(const std::vector<std::uint8_t>& blocks, int width, int height, int channels);

bool astcencInstalled();
enum class AstcProfile { Ldr, Hdr };
// astcenc -dl (LDR) or -dh (HDR) of one level's blocks put in an .astc file (ARM's header: magic
// 0x5CA1AB13, the block's dimensions, the image's as 24-bit words, then the blocks): RGBA as astcenc
// writes it into an EXR (half floats: LDR values within 2^-12).
Image astcencDecode(const ScratchDir& dir, const std::string& blocksHex, int side, int width, int height,
                    AstcProfile profile = AstcProfile::Ldr);

// The worst angle in degrees, over every texel of every level, between the xy normals of two KTX2 or DDS
// files as heightpack's reader decodes them (z rebuilt as the shader does: sqrt(1 - x^2 - y^2), or on the
// horizon past the unit circle), by atan2 of the cross and dot products: another formula than the
// library's chord.
double worstXyAngleDegrees(const std::string& stored, const std::string& reference);

}  // namespace heightpack::test
