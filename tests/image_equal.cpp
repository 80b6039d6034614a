// image_equal A B: exit 0 when two image files hold the same pixels bit for bit (file headers, such as
// a date, may differ); otherwise prints how many values differ and the first, and exits 1.
#include <cstdio>
#include <cstring>
#include <exception>

#include "io/image_io.h"

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: image_equal A B\n");
        return 2;
    }
    try {
        const wideray::Image a = wideray::readImage(argv[1], false), b = wideray::readImage(argv[2], false);
        if (a.width != b.width || a.height != b.height || a.channels != b.channels) {
            std::printf("%s is %dx%dx%d, %s is %dx%dx%d\n", argv[1], a.width, a.height, a.channels, argv[2], b.width,
                        b.height, b.channels);
            return 1;
        }
        size_t differ = 0, first = 0;
        for (size_t i = a.pixels.size(); i-- > 0;)
            if (std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(float)) != 0) ++differ, first = i;
        if (differ == 0) return 0;
        const size_t pixel = first / size_t(a.channels);
        std::printf("%s and %s: %zu of %zu values differ; first at pixel (%zu, %zu): %.9g vs %.9g\n", argv[1], argv[2],
                    differ, a.pixels.size(), pixel % size_t(a.width), pixel / size_t(a.width), a.pixels[first],
                    b.pixels[first]);
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "image_equal: %s\n", e.what());
        return 2;
    }
}
