// rangefill: one binary, one sub-command per job. Exit codes: 0 ok, 2 usage error, 3 unreadable or
// invalid input, 4 processing failure, 5 partial result. Errors are one line on stderr.
#include <cstdlib>
#include <iostream>
#include <string>

#include "cli.h"
#include "rangefill/core/errors.h"
#ifdef RANGEFILL_RESEARCH_COMMANDS
#include "research.h"
#endif

int main(int argc, char** argv) {
  using namespace rangefill;
  cli::handle_interrupts();  // before any thread exists
  CLI::App app{"rangefill: fill the holes of 3D scans and depth maps", "rangefill"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "rangefill 0.1.0");
  cli::Runner runner;
  cli::add_info_command(app, runner);
  cli::add_holes_command(app, runner);
  cli::add_repair_command(app, runner);
  cli::add_depth_command(app, runner);
#ifdef RANGEFILL_RESEARCH_COMMANDS
  cli::add_research_commands(app, runner);
#else
  for (const std::string name : {"bench", "depth-bench", "train-foe", "patch-bench"}) {
    CLI::App* sub = app.add_subcommand(name, "Not in this build (-DRANGEFILL_BUILD_RESEARCH=ON)");
    sub->allow_extras();
    sub->callback([name, &runner] {
      runner = [name]() -> int {
        throw cli::UsageError(name +
                              ": this rangefill was built without the research sub-commands "
                              "(configure with -DRANGEFILL_BUILD_RESEARCH=ON)");
      };
    });
  }
#endif

  cli::set_command_line(argc, argv);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    if (error.get_exit_code() == 0) return app.exit(error);  // --help, --version
    std::cerr << "rangefill: " << error.what() << " (see rangefill --help)\n";
    return cli::kUsage;
  }

  try {
    return runner();
  } catch (const cli::UsageError& error) {
    std::cerr << "rangefill: " << error.what() << " (see rangefill --help)\n";
    return cli::kUsage;
  } catch (const InvalidInput& error) {
    std::cerr << "rangefill: " << error.what() << "\n";
    return cli::kBadInput;
  } catch (const IoError& error) {
    std::cerr << "rangefill: " << error.what() << "\n";
    return cli::kBadInput;
  } catch (const std::bad_alloc&) {
    std::cerr << "rangefill: out of memory\n";
    return cli::kFailure;
  } catch (const std::exception& error) {
    std::cerr << "rangefill: " << error.what() << "\n";
    return cli::kFailure;
  }
}
