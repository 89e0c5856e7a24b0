// dtsl: the command line of the framework. `dtsl help` lists the commands, `dtsl COMMAND --help` shows
// one command's options.
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <new>

#include "experiments/cli.hpp"
#include "experiments/plugins.hpp"
#include "framework/core/allocator.hpp"
#include "framework/core/cores.hpp"
#include "framework/core/error.hpp"
#include "framework/core/suggest.hpp"

namespace {

/// OpenMP's threads wait at barriers by spinning unless OMP_WAIT_POLICY says passive; on a machine
/// whose other cores are taken, spinning threads steal the time the working ones need (fandisk, 6000
/// points, 2 threads while another process held one of 2 cores: 12.8 s spinning, 8.8 s passive, 8.4 s on
/// one thread). On an idle machine spinning is faster (5.7 s against 6.2 s passive), so the policy is
/// passive only when some core is busy as dtsl starts. The runtime reads the variable when it is loaded,
/// before main(), so the process starts itself again with it set. A value the user set is kept.
void prefer_passive_waiting(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY")) return;
  if (dtsl::free_cores() >= std::max(1L, ::sysconf(_SC_NPROCESSORS_ONLN))) return;
  ::setenv("OMP_WAIT_POLICY", "passive", 1);
  ::execv("/proc/self/exe", argv);  // returns only on failure: then go on as we are
}

bool wants_help(const std::vector<std::string>& args) {
  for (const std::string& a : args)
    if (a == "--help" || a == "-h") return true;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  prefer_passive_waiting(argv);
  if (argc < 2) {
    dtsl::cli::print_overview(std::cerr);
    return 2;
  }
  dtsl::configure_allocator();
  const std::string command = argv[1];
  const std::vector<std::string> all(argv, argv + argc), rest(argv + 2, argv + argc);
  dtsl::cli::Args args(rest);
  try {
    if (command == "help" || command == "--help" || command == "-h") {
      if (rest.empty()) dtsl::cli::print_overview(std::cout);
      else if (!dtsl::cli::print_command_help(rest[0], std::cout))
        throw dtsl::cli::UsageError{"help: unknown command '" + rest[0] + "'" +
                                    dtsl::did_you_mean(rest[0], dtsl::cli::command_names())};
      return 0;
    }
    if (command == "--version" || command == "version") {
      dtsl::cli::print_version(std::cout);
      return 0;
    }
    if (wants_help(rest) && dtsl::cli::print_command_help(command, std::cout)) return 0;
    dtsl::register_all_plugins();
    if (command == "run") return dtsl::cli::run_command(args, all);
    if (command == "table") return dtsl::cli::table_command(args);
    if (command == "merge") return dtsl::cli::merge_command(args, all);
    if (command == "report") return dtsl::cli::report_command(args);
    if (command == "reconstruct") return dtsl::cli::reconstruct_command(args);
    if (command == "list") return dtsl::cli::list_command(args);
    throw dtsl::cli::UsageError{"unknown command '" + command + "'" +
                                dtsl::did_you_mean(command, dtsl::cli::command_names())};
  } catch (const dtsl::cli::UsageError& e) {
    const std::vector<std::string> known = dtsl::cli::command_names();
    const bool is_command = std::find(known.begin(), known.end(), command) != known.end();
    std::cerr << "dtsl: " << e.message << "\n(see `dtsl " << (is_command ? command + " --help" : "help") << "`)\n";
    return 2;
  } catch (const dtsl::Error& e) {
    std::cerr << "dtsl: error: " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "dtsl: error: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "dtsl: error: " << e.what() << "\n";
    return 1;
  }
}
