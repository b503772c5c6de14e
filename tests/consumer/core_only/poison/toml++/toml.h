#error "heightpack::core reached an image or TOML library header (toml++/toml.h): core must not"
