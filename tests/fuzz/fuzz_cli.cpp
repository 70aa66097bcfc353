// libFuzzer harness: ptlab's command line. The input is the argument list, one argument per
// line (at most 64); it is parsed exactly as `ptlab` parses it, nothing is run.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "tools/ptlab/command_line.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<std::string> args;
  std::string arg;
  for (size_t i = 0; i < size && args.size() < 64; ++i) {
    if (data[i] == '\n') {
      args.push_back(arg);
      arg.clear();
    } else {
      arg += char(data[i]);
    }
  }
  if (!arg.empty() && args.size() < 64) args.push_back(arg);
  std::vector<char*> argv = {const_cast<char*>("ptlab")};
  for (std::string& a : args) argv.push_back(a.data());
  ptlab::CommandLine cl;
  ptlab::DefineCommandLine(&cl, "ptlab (fuzz)");
  try {
    cl.app.parse(int(argv.size()), argv.data());
  } catch (const CLI::Error&) {
    // --help, --version and usage errors end here, as in main().
  }
  return 0;
}
