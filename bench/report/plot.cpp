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

// A panel's plot command: each method's marker at (run time, y), its name
// on the line name_line(i) picks. Every row gives a label, empty but for the
// method's total: gnuplot 5.4 crashes on labels that all lie off the plot.
std::string points_against_time(std::string_view y) {
  const std::string each = "for [i = 1 : words(methods)] data skip 1 using ";
  const std::string is_total = "is_total(word(methods, i))";
  return "plot " + each + "(row(word(methods, i), $3)):(" + std::string(y) + ") \\\n" +
         "       with points pt marker(i) ps 2.2 lw 2 lc rgb colour(i) notitle, \\\n" +
         "     " + each + "(" + is_total + " ? $3 : time_low):(" + std::string(y) + "):(" + is_total +
         " ? word(methods, i) : '') \\\n" +
         "       with labels boxed center offset 0, name_line(i) textcolor rgb colour(i) notitle\n";
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
    << "  set terminal pngcairo size 1500,600 font 'sans,11'\n"
    << "} else {\n"
    << "  set terminal png size 1500,600\n"
    << "}\n"
    << "set output " << gnuplot_string(png.string()) << "\n"
    << "set datafile separator comma\n"
    << "data = " << gnuplot_string(csv.string()) << "\n"
    << "methods = " << gnuplot_string(names) << "\n"
    << "# One colour and open marker per method, all of one size. Each point carries\n"
    << "# its method's name, the first three methods' above it, the next three's below,\n"
    << "# each on a line of its own: the names of methods on one point (exact,\n"
    << "# conservative and fast, often) stay apart; an opaque box keeps the grid and\n"
    << "# the zero row's break from striking through a name. A legend row under\n"
    << "# the panels pairs every marker with its name, wherever the names land.\n"
    << "colours = '#000000 #d62728 #1f77b4 #2ca02c #ff7f0e #9467bd #8c564b #e377c2'\n"
    << "colour(i) = word(colours, (i - 1) % 8 + 1)\n"
    << "marker(i) = word('6 4 8 10 12 14 1 2', (i - 1) % 8 + 1) + 0\n"
    << "name_line(i) = ((i - 1) % 6 < 3 ? 1 : -1) * (1.3 + (i - 1) % 3)\n"
    << "is_total(m) = strcol(1) eq 'total' && strcol(2) eq m\n"
    << "row(m, x) = is_total(m) ? x : NaN\n"
    << "total(x) = strcol(1) eq 'total' && x > 0 ? x : NaN\n"
    << "# Log axes cannot show 0: zeros sit on a row of their own, below a dashed break.\n"
    << "stats data skip 1 using (total($3)) name 'TIME' nooutput\n"
    << "stats data skip 1 using (total($8 > $9 ? $8 : $9)) name 'COUNT' nooutput\n"
    << "stats data skip 1 using (total($11)) name 'TOI' nooutput\n"
    << "time_low = exists('TIME_min') ? TIME_min / 3 : 0.1\n"
    << "time_high = exists('TIME_max') ? TIME_max * 3 : 10\n"
    << "count_zero = 0.1\n"
    << "count_top = exists('COUNT_max') ? 10 ** (ceil(log10(COUNT_max)) + 1.5) : 10\n"
    << "count(n) = n > 0 ? n : count_zero\n"
    << "# TOI errors are fractions of the step: the axis ends just past 1 at most.\n"
    << "toi_decade = exists('TOI_min') ? 10 ** floor(log10(TOI_min)) : 1e-9\n"
    << "toi_zero = toi_decade / 10\n"
    << "toi_top = !exists('TOI_max') ? toi_decade * 100 : TOI_max >= 0.1 ? 1.5 : 10 ** (ceil(log10(TOI_max)) + 1.5)\n"
    << "toi(e) = e > 0 ? e : toi_zero\n"
    << "set logscale xy\n"
    << "set grid\n"
    << "set format x '10^{%L}'\n"
    << "set format y '10^{%L}'\n"
    << "set xrange [time_low : time_high]\n"
    << "set xlabel 'run time [s]'\n"
    << "set bmargin 5\n"
    << "set style textbox opaque noborder\n"
    << "set multiplot layout 1,3 title " << gnuplot_string(title) << " noenhanced\n"
    << "legend_x(i) = 0.5 + (i - (words(methods) + 1) / 2.0) * 0.11\n"
    << "do for [i = 1 : words(methods)] {\n"
    << "  set label 100 + i word(methods, i) at screen legend_x(i), screen 0.035 left offset 1.5, 0 \\\n"
    << "    point pt marker(i) ps 2.2 lw 2 lc rgb colour(i) textcolor rgb colour(i) noenhanced\n"
    << "}\n"
    << "set ylabel 'candidates'\n"
    << "set ytics 1, 10\n"
    << "set ytics add ('0' count_zero)\n"
    << "set yrange [count_zero / 30 : count_top]\n"
    << "set arrow 1 from graph 0, first sqrt(count_zero) to graph 1, first sqrt(count_zero) nohead dt 2 lc rgb '#808080'\n"
    << "set title 'false negatives (contacts missed)'\n"
    << points_against_time("count($8)")
    << "do for [i = 1 : words(methods)] { unset label 100 + i }\n"
    << "set title 'false positives (reported contacts that are none)'\n"
    << points_against_time("count($9)")
    << "set title 'largest TOI error against exact mode'\n"
    << "set ylabel 'TOI error (fraction of the step)'\n"
    << "set ytics toi_decade, 10\n"
    << "set ytics add ('0' toi_zero)\n"
    << "set yrange [toi_zero / 30 : toi_top]\n"
    << "set arrow 1 from graph 0, first toi_zero * sqrt(10) to graph 1, first toi_zero * sqrt(10) nohead dt 2 lc rgb '#808080'\n"
    << points_against_time("toi($11)")
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
