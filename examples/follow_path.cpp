// A view-dependent TIN that follows a camera path: the Refiner erases where the observer moved
// away and recovers where it came close, keeping every frame within the screen-space tolerance.
//   follow_path DEM PATH.csv FRAMES [TOLERANCE_PX]      (a path as `tinlod fly` reads it)
#include "tinlod/camera_path.hpp"
#include "tinlod/error.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/refine.hpp"

#include <cstdio>
#include <cstdlib>
#include <vector>

int main(int argc, char **argv) {
    if (argc != 4 && argc != 5) {
        std::fprintf(stderr, "usage: follow_path DEM PATH.csv FRAMES [TOLERANCE_PX]\n");
        return 2;
    }
    try {
        const tinlod::Heightfield hf = tinlod::load_heightfield(argv[1]);
        const tinlod::CameraPath path = tinlod::read_camera_path(argv[2]);
        const std::vector<tinlod::View> views = path.sample(std::atoi(argv[3]), tinlod::View{});
        tinlod::RefineOptions options;
        if (argc == 5)
            options.tolerance = std::atof(argv[4]);
        tinlod::Refiner refiner(hf, views.front(), options);
        std::printf("samples %lld first_frame_bound_px %.4f tol_px %g\n",
                    static_cast<long long>(hf.size()), refiner.first_frame().bound_px,
                    options.tolerance);
        for (std::size_t i = 1; i < views.size(); ++i) {
            const tinlod::FrameStats s = refiner.update(views[i]);
            std::printf("frame %zu nodes %lld triangles %lld erased %lld recovered %lld ms %.1f\n",
                        i, static_cast<long long>(s.nodes), static_cast<long long>(s.triangles),
                        static_cast<long long>(s.update.erased),
                        static_cast<long long>(s.update.recovered), s.total_ms);
        }
    } catch (const tinlod::Error &e) {
        std::fprintf(stderr, "follow_path: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
