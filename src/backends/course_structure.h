#pragma once
// The course's structures as structures of our backend (--accel bvh2, skip, kdtree, grid, hgrid,
// rgrid): each built over the scene's PrimitiveTable, traced one ray at a time by its kernel of the
// chosen ISA (kernels/course_kernels.h).
#include <memory>

#include "backends/backend_registry.h"
#include "backends/structure.h"

namespace wideray {

class CourseStructure : public Structure {
public:
    using Structure::Structure;

    /// One batch through the structure's kernel for `isa`: closest hits where `hits` is given,
    /// occlusion into `occluded` otherwise; `costs` (optional) receives each ray's work.
    virtual void trace(Isa isa, const Ray* rays, size_t count, Hit* hits, uint8_t* occluded,
                       TraversalCost* costs) const = 0;
    /// Kernel "auto" or "single": the structure's single-ray kernel (its only one).
    std::unique_ptr<Tracer> tracer(const KernelChoice& choice) const override;
};

std::shared_ptr<const Structure> buildBvh2(std::shared_ptr<const SceneGeometry> geometry, const StructureOptions& options);
std::shared_ptr<const Structure> buildSkipBvh(std::shared_ptr<const SceneGeometry> geometry, const StructureOptions& options);
std::shared_ptr<const Structure> buildKdTreeStructure(std::shared_ptr<const SceneGeometry> geometry,
                                                      const StructureOptions& options);
std::shared_ptr<const Structure> buildUniformGrid(std::shared_ptr<const SceneGeometry> geometry,
                                                  const StructureOptions& options);
std::shared_ptr<const Structure> buildHierarchicalGrid(std::shared_ptr<const SceneGeometry> geometry,
                                                       const StructureOptions& options);
std::shared_ptr<const Structure> buildRecursiveGrid(std::shared_ptr<const SceneGeometry> geometry,
                                                    const StructureOptions& options);

} // namespace wideray
