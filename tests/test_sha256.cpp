// SHA-256 against the FIPS 180-4 example vectors and against `sha256sum`
// (GNU coreutils) for the lengths where padding changes shape.
#include "sha256.h"

#include <catch2/catch.hpp>
#include <string>

using impulse::harness::sha256_hex;

TEST_CASE("SHA-256 matches the FIPS 180-4 example vectors", "[sha256]") {
    CHECK(sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    CHECK(sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    CHECK(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
          "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
    CHECK(sha256_hex(std::string(1000000, 'a')) ==
          "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

// 55 bytes is the longest message whose padding and length fit in one block,
// 56 the shortest that needs a second block, 64 exactly one full block of
// data. Expected values from `printf 'a%.0s' $(seq 1 N) | sha256sum`.
TEST_CASE("SHA-256 at the padding boundaries matches sha256sum", "[sha256]") {
    CHECK(sha256_hex(std::string(55, 'a')) ==
          "9f4390f8d30c2dd92ec9f095b65e2b9ae9b0a925a5258e241c9f1e910f734318");
    CHECK(sha256_hex(std::string(56, 'a')) ==
          "b35439a4ac6f0948b6d6f9e3c6af0f5f590ce20f1bde7090ef7970686ec6738a");
    CHECK(sha256_hex(std::string(64, 'a')) ==
          "ffe054fe7ae0cb6dc65c3af9b61d5209f439851db43d0ba5997337df154668eb");
}

TEST_CASE("SHA-256 treats bytes above 0x7f as unsigned", "[sha256]") {
    // printf '\xff\x80\x00' | sha256sum
    CHECK(sha256_hex(std::string("\xff\x80\x00", 3)) ==
          "e9d359479a5afbc51ee48f63fd7c4c27b4067c80c39bb1c9604917d3a6a6c8d7");
}
