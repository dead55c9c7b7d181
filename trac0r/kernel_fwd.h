// The kernel's structs, and the packed scene, that the public headers name
// but do not define. Their definitions (kernel/types.h, kernel/filter.h,
// packed_scene.h) are internal and not installed: a program built against
// trac0r does not depend on the kernel's buffer layouts. Code inside
// trac0r that reads them includes those headers.
#ifndef TRAC0R_KERNEL_FWD_H
#define TRAC0R_KERNEL_FWD_H

namespace trac0r {

struct PackedScene;

namespace kernel {
struct AccumPixel;
struct CameraRecord;
struct FilterGuide;
struct SceneView;
}  // namespace kernel

}  // namespace trac0r

#endif
