// clatter-synth: the serial synthesizer that turns soundbanks and a scene of rigid-body impulses
// into audio. This build has its command line and version report; rendering arrives with the PAN
// bank reader (see docs/architecture.md, "Stages").
#include <CLI/CLI.hpp>

#include <cstdio>

#include "core/build_info.hpp"
#include "core/errors.hpp"

int main(int argc, char** argv) {
  CLI::App app{"clatter-synth: renders debris sound from Clatter soundbanks and a scene of rigid-body impulses "
               "(serial; no mpirun needed).\nExit codes: 0 done, 1 run-time failure, 2 bad input.",
               "clatter-synth"};
  app.set_version_flag("--version", clatter::version_text("clatter-synth"));
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "clatter-synth: error: %s (see clatter-synth --help)\n", e.what());
    return clatter::kExitInputError;
  }
  std::fprintf(stderr, "clatter-synth: error: nothing to render: this build has no sound sources yet "
                       "(the PAN bank source comes first; see clatter-synth --help)\n");
  return clatter::kExitInputError;
}
