// A program outside wideray that uses it as a library: a mesh made in memory (a cube and a copy of it
// turned and moved), rays traced one at a time, as a packet and as a stream, the hits printed.
#include <cstdio>
#include <vector>

#include <wideray/wideray.h>

int main() {
    // A cube from -1 to 1: 8 corners, 12 triangles.
    const std::vector<float> corners = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1,
                                        -1, -1, 1,  1, -1, 1,  1, 1, 1,  -1, 1, 1};
    const std::vector<uint32_t> triangles = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                             3, 6, 2, 3, 7, 6, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};
    try {
        wideray::Scene scene;
        const uint32_t cube = scene.addTriangleMesh(corners, triangles);
        wideray::Transform moved;  // the cube again, 5 units along x
        moved.m[0][3] = 5;
        const uint32_t copy = scene.addInstance(cube, moved);
        scene.build();
        std::printf("wideray %s (%s): %s\n", wideray::version(), wideray::bestIsaName(), scene.description().c_str());

        // One ray at each cube, one past both.
        const wideray::Ray rays[3] = {{0, 0, -5, 0, 0, 1}, {5, 0.5f, -5, 0, 0, 1}, {10, 0, -5, 0, 0, 1}};
        for (const wideray::Ray& ray : rays) {
            const wideray::Hit hit = scene.intersect(ray);
            if (hit.valid())
                std::printf("ray from (%g, %g, %g): t = %g, %s, triangle %u\n", ray.ox, ray.oy, ray.oz, hit.t,
                            hit.geomId == cube ? "cube" : hit.geomId == copy ? "copy" : "?", hit.primId);
            else
                std::printf("ray from (%g, %g, %g): miss\n", ray.ox, ray.oy, ray.oz);
        }

        // The same rays as a packet of 4 (the fourth lane unused) and as a stream.
        wideray::RayPacket<4> packet;
        for (int i = 0; i < 3; ++i) packet.set(i, rays[i]);
        const wideray::HitPacket<4> packetHits = scene.intersect(packet);
        std::vector<wideray::Hit> streamHits(3);
        scene.intersect(rays, streamHits);
        int agree = 0;
        for (int i = 0; i < 3; ++i)
            agree += packetHits.t[i] == streamHits[i].t && packetHits.primId[i] == streamHits[i].primId;
        std::printf("packet and stream agree on %d of 3 rays; shadow ray blocked: %s\n", agree,
                    scene.occluded(wideray::Ray{0, 0, -5, 0, 0, 1, 0, 10}) ? "yes" : "no");
        return agree == 3 ? 0 : 1;
    } catch (const wideray::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
