#error "heightpack::core reached an image or TOML library header (OpenEXR/openexr.h): core must not"
