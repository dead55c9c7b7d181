// The camera as bidirectional path tracing sees it (bdpt.h): where a point
// of the scene lands in the image, and the density with which a camera
// ray picks a direction. A camera ray picks a point of its pixel uniformly
// on the image plane at distance one (trace.h's camera_plane_point), whose
// area is A = 4 extent.x extent.y: per solid angle, 1 / (A cos^3 theta)
// for a direction theta off the forward axis (pbrt-v4's PerspectiveCamera
// PDF_We). Through a thin lens the same from the point on the aperture,
// which is uniform on the lens' disc.
#ifndef TRAC0R_KERNEL_CAMERA_IMPORTANCE_H
#define TRAC0R_KERNEL_CAMERA_IMPORTANCE_H

#include "sampling.h"
#include "types.h"

T0_NAMESPACE_BEGIN

// The image plane's area at distance one.
T0_INLINE float camera_film_area(CameraRecord cam) { return 4.0f * cam.extent.x * cam.extent.y; }

// Where the ray from `lens` (the pinhole, or a point on the thin lens)
// through `point` meets the image, in pixels (x right, y down from the top
// row), and the cosine of its angle to forward; a cosine of 0 where the
// point is behind the camera. Through a lens the ray is focused: the
// image point is the one whose pinhole ray meets this ray on the plane in
// focus.
T0_INLINE float camera_raster(CameraRecord cam, float3 lens, float3 point, float2* raster) {
    const float3 w = point - lens;
    const float3 forward = xyz(cam.forward);
    const float along = dot(w, forward);
    const float distance = length(w);
    if (!(along > 0.0f) || !(distance > 0.0f)) {
        return 0.0f;
    }
    float3 plane = w / along;  // on the image plane at distance one
    if (cam.extent.z > 0.0f) {
        // The point of the plane in focus on this ray, seen from the
        // pinhole, scaled back to distance one.
        plane = (lens + w * (cam.extent.w / along) - xyz(cam.position)) / cam.extent.w;
    }
    const float sx = dot(plane, xyz(cam.right)) / cam.extent.x;
    const float sy = dot(plane, xyz(cam.up)) / cam.extent.y;
    *raster =
        make_float2(0.5f * (sx + 1.0f) * (float)cam.size.x, 0.5f * (1.0f - sy) * (float)cam.size.y);
    return along / distance;
}

// The pixel a raster position lies in, or -1 outside the image.
T0_INLINE int camera_pixel(CameraRecord cam, float2 raster) {
    if (!(raster.x >= 0.0f && raster.y >= 0.0f && raster.x < (float)cam.size.x &&
          raster.y < (float)cam.size.y)) {
        return -1;
    }
    t0_u32 x = (t0_u32)raster.x;
    t0_u32 y = (t0_u32)raster.y;
    x = x < cam.size.x ? x : cam.size.x - 1u;  // a float rounded up to the size
    y = y < cam.size.y ? y : cam.size.y - 1u;
    return (int)(y * cam.size.x + x);
}

// The density per solid angle with which a camera ray from `lens` takes
// unit direction w: 1 / (A cos^3 theta) inside the image, else zero.
T0_INLINE float camera_pdf_direction(CameraRecord cam, float3 lens, float3 w) {
    float2 raster;
    const float c = camera_raster(cam, lens, lens + w, &raster);
    if (!(c > 0.0f) || camera_pixel(cam, raster) < 0) {
        return 0.0f;
    }
    return 1.0f / (camera_film_area(cam) * c * c * c);
}

// A point on the thin lens (uniform on its disc), or the pinhole: as
// trace.h's camera_lens_ray picks it from the same two numbers.
T0_INLINE float3 camera_lens_point(CameraRecord cam, float2 u) {
    if (!(cam.extent.z > 0.0f)) {
        return xyz(cam.position);
    }
    const float r = cam.extent.z * sqrt(u.x);
    const float2_cs turn = turn_cos_sin(u.y);
    return xyz(cam.position) + xyz(cam.right) * (r * turn.c) + xyz(cam.up) * (r * turn.s);
}

T0_NAMESPACE_END

#endif
