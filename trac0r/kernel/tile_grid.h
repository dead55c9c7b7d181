// The image cut into tiles of T0_TILE x T0_TILE pixels, numbered row by
// row: how many there are (tile_count) and which pixels each holds
// (tile_rect), for both backends and the host that launches them.
#ifndef TRAC0R_KERNEL_TILE_GRID_H
#define TRAC0R_KERNEL_TILE_GRID_H

#include "compat.h"

// The CPU backend renders a tile at a time, the OpenCL program (with the
// BVH) a tile a work-group, and a tile's camera rays share the BVH leaves
// they may enter (kernel/bundle.h, bundle_leaves).
#define T0_TILE 8

T0_NAMESPACE_BEGIN

// The pixels [x0, x1) x [y0, y1) of an image.
typedef struct TileRect {
    t0_u32 x0;
    t0_u32 y0;
    t0_u32 x1;
    t0_u32 y1;
} TileRect;

// Tiles along a side of `pixels` pixels.
T0_INLINE t0_u32 tiles_along(t0_u32 pixels) { return (pixels + T0_TILE - 1u) / T0_TILE; }

T0_INLINE t0_u32 tile_count(t0_u32 width, t0_u32 height) {
    return tiles_along(width) * tiles_along(height);
}

// Tile `tile` of a width x height image: T0_TILE x T0_TILE pixels, but for
// the last column and row of tiles, which may be narrower.
T0_INLINE TileRect tile_rect(t0_u32 tile, t0_u32 width, t0_u32 height) {
    const t0_u32 across = tiles_along(width);
    TileRect r;
    r.x0 = tile % across * T0_TILE;
    r.y0 = tile / across * T0_TILE;
    r.x1 = r.x0 + T0_TILE < width ? r.x0 + T0_TILE : width;
    r.y1 = r.y0 + T0_TILE < height ? r.y0 + T0_TILE : height;
    return r;
}

T0_NAMESPACE_END

#endif
