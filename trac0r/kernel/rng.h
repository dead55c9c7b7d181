// Random numbers: xorshift1024* (Vigna 2014), seeded by xorshift64*.
//
// Each pixel of each frame gets its own generator, seeded from
// (seed, pixel, frame) alone, so a render is a pure function of its inputs
// and both backends draw the same numbers.
#ifndef TRAC0R_KERNEL_RNG_H
#define TRAC0R_KERNEL_RNG_H

#include "compat.h"

T0_NAMESPACE_BEGIN

typedef struct Rng {
    t0_u64 s[16];
    int p;
    // Seeding is lazy: s[0, filled) hold their words; xorshift1024* reads
    // the rest in order, s[k] first at the k-th output, so each is made
    // from seed_state then (the same words as filling all sixteen at once,
    // without the ones a short path never reads). A state set by hand
    // sets filled to 16.
    int filled;
    t0_u64 seed_state;
} Rng;

// xorshift64* (Vigna, "An experimental exploration of Marsaglia's xorshift
// generators, scrambled"): advances *state and returns the scrambled output.
T0_INLINE t0_u64 xorshift64star_next(t0_u64* state) {
    t0_u64 x = *state;
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    *state = x;
    return x * 2685821657736338717UL;
}

// xorshift1024* as published (multiplier 1181783497276652981).
T0_INLINE t0_u64 xorshift1024star_next(Rng* rng) {
    const t0_u64 s0 = rng->s[rng->p];
    rng->p = (rng->p + 1) & 15;
    if (rng->p == rng->filled) {
        rng->s[rng->p] = xorshift64star_next(&rng->seed_state);
        ++rng->filled;
    }
    t0_u64 s1 = rng->s[rng->p];
    s1 ^= s1 << 31;
    rng->s[rng->p] = s1 ^ s0 ^ (s1 >> 11) ^ (s0 >> 30);
    return rng->s[rng->p] * 1181783497276652981UL;
}

// Fills the 1024-bit state from a 64-bit seed with xorshift64*, as the
// xorshift authors recommend: its first word now, the others as they are
// first read (Rng.filled). A zero seed is mapped to a fixed non-zero one
// (xorshift64* must not start at zero).
T0_INLINE void rng_seed(Rng* rng, t0_u64 seed) {
    rng->seed_state = seed != 0UL ? seed : 0x9E3779B97F4A7C15UL;
    rng->s[0] = xorshift64star_next(&rng->seed_state);
    rng->filled = 1;
    rng->p = 0;
}

// The 64-bit finaliser of MurmurHash3: spreads (seed, pixel, frame), which
// differ in few bits between neighbours, over all 64 bits before seeding.
T0_INLINE t0_u64 mix64(t0_u64 x) {
    x ^= x >> 33;
    x *= 0xFF51AFD7ED558CCDUL;
    x ^= x >> 33;
    x *= 0xC4CEB9FE1A85EC53UL;
    x ^= x >> 33;
    return x;
}

T0_INLINE void rng_seed_pixel(Rng* rng, t0_u64 seed, t0_u32 pixel, t0_u32 frame) {
    t0_u64 key = mix64(seed ^ mix64(((t0_u64)frame << 32) | (t0_u64)pixel));
    rng_seed(rng, key);
}

// A float in [0, 1): the top 24 bits, so every value is exact and the
// largest is 1 - 2^-24.
T0_INLINE float rng_float(Rng* rng) {
    return (float)(xorshift1024star_next(rng) >> 40) * (1.0f / 16777216.0f);
}

// Two of them, x drawn first.
T0_INLINE float2 rng_float2(Rng* rng) {
    const float x = rng_float(rng);
    const float y = rng_float(rng);
    return make_float2(x, y);
}

T0_NAMESPACE_END

#endif
