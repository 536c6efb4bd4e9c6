// libFuzzer target: the numbers of the command line, from the text a user types to the
// printed result (nsbridge criterion, and nsbridge lcp's --tol and --max-iter).
//
// Input: the first byte selects the command; the rest is split at newlines into the option
// values. A bad value must end in CLI11's parse error or the commands' InputError (exit 2);
// anything else is a bug, and so is a printed "nan" or "inf" (JSON never carries them, and a
// non-finite criterion is refused).
#include "app/commands.hpp"

#include <cstddef>
#include <cstdint>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace nsb::app {
int& exit_code() {
  static int code = 0;
  return code;
}
}  // namespace nsb::app

namespace {

std::vector<std::string> fields(const std::string& text, std::size_t count) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string f; out.size() < count && std::getline(in, f);) out.push_back(f);
  while (out.size() < count) out.emplace_back("1");
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const bool criterion = (data[0] & 1) == 0;
  const bool json = (data[0] & 2) != 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  std::vector<std::string> args{"nsbridge"};
  if (criterion) {
    const auto v = fields(text, 4);
    args.insert(args.end(), {"criterion", "--skew", v[0], "--width", v[1], "--length", v[2],
                             "--friction", v[3]});
  } else {
    const auto v = fields(text, 2);
    args.insert(args.end(), {"lcp", "data/siconos-lcp/lcp_trivial.dat", "--tol", v[0],
                             "--max-iter", v[1]});
  }
  if (json) args.emplace_back("--json");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());

  CLI::App app{"nsbridge"};
  app.require_subcommand(1);
  nsb::app::add_lcp_command(app);
  nsb::app::add_criterion_command(app);
  std::ostringstream captured;
  std::streambuf* const saved = std::cout.rdbuf(captured.rdbuf());
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::ParseError&) {
  } catch (const nsb::app::InputError&) {
  } catch (const std::invalid_argument&) {
  } catch (...) {
    std::cout.rdbuf(saved);
    throw;
  }
  std::cout.rdbuf(saved);
  // The criterion refuses non-finite results, and JSON has null for them: neither ever
  // prints a word nan or inf. (lcp's text output may name a solver's NaN residual, an
  // outcome with exit 1, and its legend holds "||.||_inf".)
  if (criterion || json) {
    std::istringstream words(captured.str());
    for (std::string w; words >> w;) {
      while (!w.empty() && (w.back() == ',' || w.back() == '}' || w.back() == ']')) w.pop_back();
      while (!w.empty() && (w.front() == '[' || w.front() == '-')) w.erase(0, 1);
      if (w == "nan" || w == "inf") {
        std::cerr << "non-finite number printed:\n" << captured.str();
        __builtin_trap();
      }
    }
  }
  return 0;
}
