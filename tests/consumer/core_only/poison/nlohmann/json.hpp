#error "heightpack::core reached an image or TOML library header (nlohmann/json.hpp): core must not"
