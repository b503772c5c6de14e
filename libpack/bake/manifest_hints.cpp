#include "manifest_hints.hpp"

#include "heightpack/io/read.hpp"

namespace heightpack::detail {

namespace {

std::string quotedChannelNames() {
    std::string text;
    for (const std::string& name : allNames<ChannelSelect>()) text += (text.empty() ? "\"" : "\", \"") + name;
    return text + "\"";
}

}  // namespace

Error inManifestTerms(Error error) {
    const std::string size = error.fixArgs.empty() ? std::string() : error.fixArgs[0];
    switch (error.fix) {
        case Fix::ChooseChannel:
            error.hint = "choose the height channel with channel = " + quotedChannelNames() + " or a channel's name";
            break;
        case Fix::ChooseExistingChannel: error.hint = "pick one it has with channel = \"NAME\""; break;
        case Fix::ResizeToPowerOfTwo:
        case Fix::ResizeOrLevelZeroOnly: error.hint = "set resize = true to resample it to " + size; break;
        case Fix::AddShift: error.hint = "give a source with Dx, Dy channels, or set choppiness = 0"; break;
        case Fix::AddFoam: error.hint = "give a source with a Foam channel, or set foam = false"; break;
        default: return error;  // no manifest key for it
    }
    error.fix = Fix::None;
    error.fixArgs.clear();
    return error;
}

}  // namespace heightpack::detail
