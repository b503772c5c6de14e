#error "heightpack::core reached an image or TOML library header (OpenImageIO/imagebuf.h): core must not"
