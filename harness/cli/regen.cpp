// `impulse regen [SCENE...]`: the goldens of the project found from the
// current folder, regenerated after an intended change. The verb the gate's
// hints name; scripts/regen-goldens builds the tool and calls it from the
// caller's folder, so relative scene paths and --root . mean what they say.
#include "cli.h"

namespace impulse::harness::cli {

int regen_verb(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    return write_goldens("regen", args, out, err);
}

} // namespace impulse::harness::cli
