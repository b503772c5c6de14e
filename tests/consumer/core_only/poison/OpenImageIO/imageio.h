#error "heightpack::core reached an image or TOML library header (OpenImageIO/imageio.h): core must not"
