#include "hints.hpp"

#include "heightpack/io/read.hpp"

namespace heightpack::view {

std::string viewerHint(const Error& error) {
    switch (error.fix) {
        case Fix::ChooseChannel:
            return "choose the height channel with --channel " + joinedNames<ChannelSelect>("|") + " or a channel's name";
        case Fix::ChooseExistingChannel: return "pick one it has with --channel";
        default: return error.hint;  // the viewer resamples, writes nothing but screenshots, and runs no jobs
    }
}

}  // namespace heightpack::view
