#include "cli.h"

int main(int argc, char** argv) {
    return impulse::harness::cli::main(argc, argv);
}
