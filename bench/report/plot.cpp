#include "plot.hpp"

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace batchccd::bench {
namespace {

namespace fs = std::filesystem;

// A gnuplot string literal: single quotes, doubled inside.
std::string gnuplot_string(std::string_view text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string read_all(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

std::optional<fs::path> find_gnuplot() {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return std::nullopt;
  std::istringstream directories(path);
  for (std::string directory; std::getline(directories, directory, ':');) {
    if (directory.empty()) continue;
    const fs::path candidate = fs::path(directory) / "gnuplot";
    if (::access(candidate.c_str(), X_OK) == 0 && !fs::is_directory(candidate)) return candidate;
  }
  return std::nullopt;
}

std::string plot_script(std::string_view title, const fs::path& csv, const fs::path& png,
                        const std::vector<std::string>& methods) {
  // CSV columns: 1 input, 2 method, 3 seconds, 8 false_negatives,
  // 9 false_positives, 11 toi_error_max (comparison_format.cpp).
  std::string names;
  for (const std::string& method : methods) names += (names.empty() ? "" : " ") + method;
  std::ostringstream s;
  s << "# Draws " << csv.string() << " (batchccd_report's CSV) into " << png.string()
    << ": gnuplot plot.gp\n"
    << "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
    << "  set terminal pngcairo size 1400,620 font 'sans,11'\n"
    << "} else {\n"
    << "  set terminal png size 1400,620\n"
    << "}\n"
    << "set output " << gnuplot_string(png.string()) << "\n"
    << "set datafile separator comma\n"
    << "data = " << gnuplot_string(csv.string()) << "\n"
    << "methods = " << gnuplot_string(names) << "\n"
    << "# One colour and open marker per method, later ones smaller: equal points stay visible.\n"
    << "colours = '#000000 #d62728 #1f77b4 #2ca02c #ff7f0e #9467bd #8c564b #e377c2'\n"
    << "colour(i) = word(colours, (i - 1) % 8 + 1)\n"
    << "marker(i) = word('6 4 8 10 12 14 1 2', (i - 1) % 8 + 1) + 0\n"
    << "size(i) = 3.2 - 0.4 * ((i - 1) % 6)\n"
    << "row(m, x) = strcol(1) eq 'total' && strcol(2) eq m ? x : NaN\n"
    << "# Log axes cannot show 0: zeros sit on a row of their own below the decades, ticked 0.\n"
    << "stats data skip 1 using (strcol(1) eq 'total' && $11 > 0 ? $11 : 1) nooutput\n"
    << "toi_decade = 10 ** floor(log10(STATS_min))\n"
    << "toi_zero = toi_decade / 100\n"
    << "wrong_zero = 0.1\n"
    << "wrong(fn, fp) = fn + fp > 0 ? fn + fp : wrong_zero\n"
    << "toi(e) = e > 0 ? e : toi_zero\n"
    << "set logscale xy\n"
    << "set grid\n"
    << "set key outside right top vertical Left reverse noautotitle\n"
    << "set xlabel 'run time [s]'\n"
    << "set offsets graph 0.1, graph 0.1, graph 0.1, graph 0.05\n"
    << "set multiplot layout 1,2 title " << gnuplot_string(title) << " noenhanced\n"
    << "set title 'wrong decisions (false negatives + false positives)'\n"
    << "set ylabel 'wrong decisions'\n"
    << "set ytics 1, 10\n"
    << "set ytics add ('0' wrong_zero)\n"
    << "set yrange [wrong_zero / 2 : *]\n"
    << "set key off\n"
    << "plot for [i = 1 : words(methods)] data skip 1 using (row(word(methods, i), $3)):(wrong($8, $9)) \\\n"
    << "     with points pt marker(i) ps size(i) lw 2 lc rgb colour(i)\n"
    << "set title 'largest TOI error against exact mode'\n"
    << "set ylabel 'TOI error (fraction of the step)'\n"
    << "set format y '10^{%L}'\n"
    << "set ytics toi_decade, 10\n"
    << "set ytics add ('0' toi_zero)\n"
    << "set yrange [toi_zero / 2 : *]\n"
    << "set key on\n"
    << "plot for [i = 1 : words(methods)] data skip 1 using (row(word(methods, i), $3)):(toi($11)) \\\n"
    << "     with points pt marker(i) ps size(i) lw 2 lc rgb colour(i) title word(methods, i)\n"
    << "unset multiplot\n";
  return s.str();
}

void run_gnuplot(const fs::path& gnuplot, const fs::path& directory, const std::string& script) {
  // gnuplot's messages go to a log, shown only when it fails.
  const fs::path log = fs::absolute(directory) / (script + ".log");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, directory.c_str());
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  const std::string program = fs::absolute(gnuplot).string();
  std::vector<char*> argv = {const_cast<char*>(program.c_str()), const_cast<char*>(script.c_str()),
                             nullptr};
  pid_t child = 0;
  const int spawned = posix_spawn(&child, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  int status = 0;
  if (spawned == 0 && ::waitpid(child, &status, 0) < 0) status = -1;
  const std::string messages = read_all(log);
  std::error_code ignored;
  fs::remove(log, ignored);
  if (spawned != 0)
    throw std::runtime_error("cannot run " + program + ": " + std::generic_category().message(spawned));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("gnuplot " + (directory / script).string() + " failed:\n" + messages);
}

}  // namespace batchccd::bench
