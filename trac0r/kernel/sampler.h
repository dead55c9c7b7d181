// The numbers a path is made from. Each is a pure function of (seed, pixel,
// frame, dimension), so the same seed gives the same image on both
// backends, and frame n of a pixel is its n-th sample: the progressive
// one-sample-per-frame accumulation needs no sample count up front.
//
// Two samplers (T0_FEATURE_SOBOL, `--sampler`):
// - random: the thesis' xorshift1024* (rng.h), one generator per pixel and
//   frame, drawn in the order the path asks;
// - sobol: Owen-scrambled Sobol points with hash-based scrambling (Burley,
//   "Practical Hash-based Owen Scrambling", JCGT 2020). Every draw is the
//   first one or two Sobol dimensions, the (0,2)-sequence, "padded": each
//   dimension below gets its own shuffle of the sample index and its own
//   scramble, both seeded by a hash of (seed, pixel, dimension). So for
//   any 2^k frames from the first, each draw's points form a (0,k,2)-net,
//   one point in every elementary interval of area 2^-k, whatever the
//   other draws do.
//
// The dimensions, in the order a path uses them (T0_DIM):
//   0                pixel jitter (2-D)
//   T0_DIM_LENS      the point on a thin lens (2-D), drawn only when the
//                    camera's aperture is open; with random, right after
//                    the jitter. Its own dimension (-1, out of the way of
//                    the path's), so a pinhole draws exactly what it drew
//                    before lenses existed.
//   then, for each vertex `depth` from 0, at 1 + 4 * depth:
//   + T0_DIM_LIGHT_PICK   which light (1-D)
//   + T0_DIM_LIGHT_POINT  the point on it (2-D)
//   + T0_DIM_ROULETTE     Russian roulette (1-D)
//   + T0_DIM_MATERIAL     the scattered direction (2-D; glass chooses
//                         reflection or refraction with the first)
//   T0_DIM_LIGHT_TREE(depth)  the walk down the light tree (1-D), drawn only
//                    with T0_FEATURE_LIGHT_TREE; negative (-2 - depth), out
//                    of the way of the path's, so scenes without the tree
//                    draw exactly what they drew before it existed.
//   T0_DIM_LOBE(depth)  which lobe of a microfacet material (1-D: rough
//                    glass, plastic, principled); negative too, below the
//                    tree's for any depth a path may reach.
#ifndef TRAC0R_KERNEL_SAMPLER_H
#define TRAC0R_KERNEL_SAMPLER_H

#include "rng.h"
#include "types.h"

T0_NAMESPACE_BEGIN

#define T0_DIM_PIXEL 0
#define T0_DIM_LENS (-1)
#define T0_DIM_LIGHT_PICK 0
#define T0_DIM_LIGHT_POINT 1
#define T0_DIM_ROULETTE 2
#define T0_DIM_MATERIAL 3
#define T0_DIMS_PER_VERTEX 4
#define T0_DIM(depth, slot) (1 + (depth)*T0_DIMS_PER_VERTEX + (slot))
#define T0_DIM_LIGHT_TREE(depth) (-2 - (depth))
#define T0_DIM_LOBE(depth) (-(1 << 20) - (depth))

typedef struct Sampler {
    Rng rng;       // random: the pixel's generator for this frame
    t0_u32 key;    // sobol: a hash of (seed, pixel)
    t0_u32 index;  // sobol: the sample's index in the pixel's sequence (the frame),
                   // bit-reversed (what the index shuffle takes)
    int sobol;     // which of the two
} Sampler;

T0_INLINE t0_u32 reverse_bits32(t0_u32 x) {
    x = ((x & 0xAAAAAAAAu) >> 1) | ((x & 0x55555555u) << 1);
    x = ((x & 0xCCCCCCCCu) >> 2) | ((x & 0x33333333u) << 2);
    x = ((x & 0xF0F0F0F0u) >> 4) | ((x & 0x0F0F0F0Fu) << 4);
    x = ((x & 0xFF00FF00u) >> 8) | ((x & 0x00FF00FFu) << 8);
    return (x >> 16) | (x << 16);
}

// A 32-bit integer hash (Wellons' "lowbias32"): the seeds of the scrambles.
T0_INLINE t0_u32 hash32(t0_u32 x) {
    x ^= x >> 16;
    x *= 0x7FEB352Du;
    x ^= x >> 15;
    x *= 0x846CA68Bu;
    x ^= x >> 16;
    return x;
}

// Base-2 Owen scrambling of a bit-reversed integer: each bit is flipped by a
// hash of the bits below it, which in the reversed order are the more
// significant digits. Vegdahl's improvement of the Laine-Karras
// permutation ("Building a better LK hash", 2021).
T0_INLINE t0_u32 reversed_owen(t0_u32 x, t0_u32 seed) {
    x ^= x * 0x3D20ADEAu;
    x += seed;
    x *= (seed >> 16) | 1u;
    x ^= x * 0x05526C56u;
    x ^= x * 0x53A22864u;
    return x;
}

// The second Sobol dimension of index i, bit-reversed (bit r holds the
// digit of weight 2^-(r+1)). Its generator matrix is Pascal's triangle mod
// 2: digit r is the parity of the index bits c with r a submask of c
// (Lucas), a superset sum over the five bits of a bit's position.
T0_INLINE t0_u32 sobol1_reversed(t0_u32 i) {
    i ^= (i >> 1) & 0x55555555u;
    i ^= (i >> 2) & 0x33333333u;
    i ^= (i >> 4) & 0x0F0F0F0Fu;
    i ^= (i >> 8) & 0x00FF00FFu;
    i ^= (i >> 16) & 0x0000FFFFu;
    return i;
}

// A float in [0, 1) from the top 24 bits, as rng_float.
T0_INLINE float unit_float(t0_u32 x) { return (float)(x >> 8) * (1.0f / 16777216.0f); }

// The sample index of `dim`, shuffled by a nested uniform scramble (an Owen
// scramble of the index's bits): the first 2^k indices go to an aligned
// block of 2^k, so a prefix keeps its stratification.
T0_INLINE t0_u32 sobol_shuffled_index(const Sampler* s, t0_u32 dim_seed) {
    return reverse_bits32(reversed_owen(s->index, dim_seed));
}

// The seed of dimension `dim`'s shuffle: one hash of the pixel's key and
// the dimension spread by the golden ratio (no two dimensions of a pixel
// share a seed, as the hash is a bijection).
T0_INLINE t0_u32 sobol_dim_seed(const Sampler* s, int dim) {
    return hash32(s->key + (t0_u32)dim * 0x9E3779B9u);
}

T0_FORCE_INLINE float sample_1d(Sampler* s, int dim) {
    if (!s->sobol) {
        return rng_float(&s->rng);
    }
    const t0_u32 seed = sobol_dim_seed(s, dim);
    const t0_u32 i = sobol_shuffled_index(s, seed);
    // Dimension 0 is the van der Corput sequence: i bit-reversed, whose
    // reversed form is i itself.
    return unit_float(reverse_bits32(reversed_owen(i, hash32(seed))));
}

// Two numbers for one 2-D draw; with random, x is drawn first.
T0_FORCE_INLINE float2 sample_2d(Sampler* s, int dim) {
    if (!s->sobol) {
        return rng_float2(&s->rng);
    }
    const t0_u32 seed = sobol_dim_seed(s, dim);
    const t0_u32 i = sobol_shuffled_index(s, seed);
    const t0_u32 seed_x = hash32(seed);
    const t0_u32 seed_y = hash32(seed_x);
    return make_float2(unit_float(reverse_bits32(reversed_owen(i, seed_x))),
                       unit_float(reverse_bits32(reversed_owen(sobol1_reversed(i), seed_y))));
}

// A vertex's numbers (T0_DIM(depth, ...)). With sobol, sampler_start_vertex
// draws them all at once: each draw is a chain of dependent multiplies
// and bit reversals, and four independent chains side by side keep the
// processor busy where one alone would wait on each multiply. With random
// the vertex_* calls draw as the path asks, in the thesis' order.
typedef struct VertexDraws {
    float light_pick;
    float2 light_point;
    float roulette;
    float2 material;  // glass takes x alone (sample_1d's number for the dimension)
} VertexDraws;

T0_INLINE void sampler_start_vertex(Sampler* s, int depth, int lights, VertexDraws* v) {
    if (!s->sobol) {
        return;
    }
    if (lights) {
        v->light_pick = sample_1d(s, T0_DIM(depth, T0_DIM_LIGHT_PICK));
        v->light_point = sample_2d(s, T0_DIM(depth, T0_DIM_LIGHT_POINT));
    }
    v->roulette = sample_1d(s, T0_DIM(depth, T0_DIM_ROULETTE));
    v->material = sample_2d(s, T0_DIM(depth, T0_DIM_MATERIAL));
}

// A number of the vertex: the one sampler_start_vertex drew, or the next
// random one.
T0_INLINE float vertex_1d(Sampler* s, float drawn) { return s->sobol ? drawn : rng_float(&s->rng); }

T0_INLINE float2 vertex_2d(Sampler* s, float2 drawn) {
    return s->sobol ? drawn : rng_float2(&s->rng);
}

// The pixel's sampler for `frame`: sobol where the scene's features say.
T0_INLINE void sampler_start(Sampler* s, int sobol, t0_u64 seed, t0_u32 pixel, t0_u32 frame) {
    s->sobol = sobol;
    if (sobol) {
        const t0_u64 key = mix64(seed ^ mix64((t0_u64)pixel));
        s->key = (t0_u32)(key ^ (key >> 32));
        s->index = reverse_bits32(frame);
    } else {
        s->key = 0u;
        s->index = 0u;
        rng_seed_pixel(&s->rng, seed, pixel, frame);
    }
}

T0_NAMESPACE_END

#endif
