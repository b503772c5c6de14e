// Internal: every key each table of a manifest takes (docs/manifest.md, "Every key"), and the look over
// the whole manifest for keys no table takes, which runs before any value is judged: a misspelt key is the
// likelier mistake than the key it leaves missing, so it is the one named, wherever it is.
#pragma once

#include <toml++/toml.h>

#include <string>
#include <string_view>
#include <vector>

namespace heightpack::detail {

// The tables of a manifest, each with its own keys.
enum class ManifestTable { Top, Defaults, Displacement, Synth, Normals, Octave, Fresnel, Foam };

// The keys a table takes.
const std::vector<std::string_view>& keysOf(ManifestTable table);

// Throws the Error for the manifest's first key (in file order) that its table does not take, naming
// the nearest key the table does take. A table of the wrong type is left for the parser to report.
void rejectUnknownKeys(const toml::table& root, const std::string& file);

}  // namespace heightpack::detail
