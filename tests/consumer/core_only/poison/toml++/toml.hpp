#error "heightpack::core reached an image or TOML library header (toml++/toml.hpp): core must not"
