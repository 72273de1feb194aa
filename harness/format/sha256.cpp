// A plain transcription of FIPS 180-4, section 6.2: no external library, so the
// fingerprint is the same wherever the harness is built.
#include "sha256.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace impulse::harness {

namespace {

using Word = std::uint32_t;
using State = std::array<Word, 8>;

// FIPS 180-4 section 4.2.2: the first 32 bits of the fractional parts of the
// cube roots of the first 64 primes.
constexpr std::array<Word, 64> round_constants = {
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5,
    0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174,
    0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
    0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967,
    0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
    0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
    0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
    0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2};

// Section 5.3.3: the first 32 bits of the fractional parts of the square roots
// of the first 8 primes.
constexpr State initial_hash = {0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a,
                                0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19};

constexpr std::size_t block_bytes = 64;

// Rotate right; n is always in 1..31 here, so neither shift is by 32.
Word rotr(Word x, unsigned n) {
    return (x >> n) | (x << (32U - n));
}

// The six logical functions of section 4.1.2.
Word ch(Word x, Word y, Word z) {
    return (x & y) ^ (~x & z);
}
Word maj(Word x, Word y, Word z) {
    return (x & y) ^ (x & z) ^ (y & z);
}
Word big_sigma0(Word x) {
    return rotr(x, 2) ^ rotr(x, 13) ^ rotr(x, 22);
}
Word big_sigma1(Word x) {
    return rotr(x, 6) ^ rotr(x, 11) ^ rotr(x, 25);
}
Word small_sigma0(Word x) {
    return rotr(x, 7) ^ rotr(x, 18) ^ (x >> 3);
}
Word small_sigma1(Word x) {
    return rotr(x, 17) ^ rotr(x, 19) ^ (x >> 10);
}

// Section 5.1.1: append a 1 bit, zeros up to 56 bytes mod 64, then the message
// length in bits as a 64-bit big-endian number.
std::vector<std::uint8_t> pad(const std::string& bytes) {
    std::vector<std::uint8_t> message(bytes.begin(), bytes.end());
    const std::uint64_t length_in_bits = static_cast<std::uint64_t>(bytes.size()) * 8U;
    message.push_back(0x80);
    while (message.size() % block_bytes != block_bytes - 8) {
        message.push_back(0x00);
    }
    for (int shift = 56; shift >= 0; shift -= 8) {
        message.push_back(static_cast<std::uint8_t>(length_in_bits >> shift));
    }
    return message;
}

// Words are read big-endian (section 3.1), whatever the host's byte order.
Word read_big_endian(const std::uint8_t* bytes) {
    return (Word{bytes[0]} << 24) | (Word{bytes[1]} << 16) | (Word{bytes[2]} << 8) | Word{bytes[3]};
}

// Section 6.2.2: one 64-byte block folded into the running hash.
void compress(State& hash, const std::uint8_t* block) {
    std::array<Word, 64> schedule{};
    for (std::size_t t = 0; t < 16; ++t) {
        schedule[t] = read_big_endian(block + 4 * t);
    }
    for (std::size_t t = 16; t < 64; ++t) {
        schedule[t] = small_sigma1(schedule[t - 2]) + schedule[t - 7] +
                      small_sigma0(schedule[t - 15]) + schedule[t - 16];
    }

    Word a = hash[0], b = hash[1], c = hash[2], d = hash[3];
    Word e = hash[4], f = hash[5], g = hash[6], h = hash[7];
    for (std::size_t t = 0; t < 64; ++t) {
        const Word t1 = h + big_sigma1(e) + ch(e, f, g) + round_constants[t] + schedule[t];
        const Word t2 = big_sigma0(a) + maj(a, b, c);
        h = g;
        g = f;
        f = e;
        e = d + t1;
        d = c;
        c = b;
        b = a;
        a = t1 + t2;
    }
    hash[0] += a;
    hash[1] += b;
    hash[2] += c;
    hash[3] += d;
    hash[4] += e;
    hash[5] += f;
    hash[6] += g;
    hash[7] += h;
}

std::string to_hex(const State& hash) {
    static const char digits[] = "0123456789abcdef";
    std::string hex;
    hex.reserve(64);
    for (const Word word : hash) {
        for (int shift = 28; shift >= 0; shift -= 4) {
            hex.push_back(digits[(word >> shift) & 0xFU]);
        }
    }
    return hex;
}

} // namespace

std::string sha256_hex(const std::string& bytes) {
    const std::vector<std::uint8_t> message = pad(bytes);
    State hash = initial_hash;
    for (std::size_t offset = 0; offset < message.size(); offset += block_bytes) {
        compress(hash, message.data() + offset);
    }
    return to_hex(hash);
}

} // namespace impulse::harness
