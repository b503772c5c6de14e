#error "heightpack::core reached an image or TOML library header (OpenEXR/ImfHeader.h): core must not"
