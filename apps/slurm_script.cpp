#include "apps/slurm_script.h"

#include <cstdio>
#include <system_error>

#include "base/error.h"

namespace svbrdf {

namespace fs = std::filesystem;

void SlurmJobOptions::add_to(CLI::App& app, const std::string& what) {
  app.add_option("--slurm-partition", partition, "with --slurm: sbatch's --partition for both jobs");
  app.add_option("--slurm-account", account, "with --slurm: sbatch's --account for both jobs");
  app.add_option("--slurm-time", time, "with --slurm: sbatch's --time limit of " + what);
  app.add_option(
      "--slurm-option", sbatch_options,
      "with --slurm: another sbatch option for both jobs, e.g. --slurm-option=--mem=4G (repeatable)");
}

// `text` as one word of a POSIX shell command: in single quotes, each ' as '\'' (POSIX.1-2017, Shell
// Command Language §2.2.2: nothing inside single quotes is special but the quote itself).
std::string shell_quoted(const std::string& text) {
  std::string out = "'";
  for (const char ch : text) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return out + "'";
}

// `text` as one argument of an #SBATCH line: in double quotes, each \ and " escaped by a backslash.
// sbatch reads a directive's argument up to unquoted white space and takes single or double quotes
// and backslash escapes (Slurm's sbatch, _get_argument); unquoted, a space would end the path and a #
// begin a comment.
std::string directive_quoted(const std::string& text) {
  std::string out = "\"";
  for (const char ch : text) {
    if (ch == '\\' || ch == '"') out += '\\';
    out += ch;
  }
  return out + "\"";
}

// A path as sbatch's --output takes it: its % doubled, for %A, %a and %j are the job's numbers there
// (sbatch(1), filename pattern: "%%" is the character %).
std::string output_pattern(const std::string& path) {
  std::string out;
  for (const char ch : path) out += ch == '%' ? std::string("%%") : std::string(1, ch);
  return out;
}

// The #SBATCH lines both jobs share: where they run and log, and what the user passed on.
std::string common_directives(const SlurmJobOptions& s, const fs::path& folder) {
  std::string out = "#SBATCH --chdir=" + directive_quoted(folder.string()) + "\n";
  if (!s.partition.empty()) out += "#SBATCH --partition=" + s.partition + "\n";
  if (!s.account.empty()) out += "#SBATCH --account=" + s.account + "\n";
  if (!s.time.empty()) out += "#SBATCH --time=" + s.time + "\n";
  for (const std::string& o : s.sbatch_options) out += "#SBATCH " + o + "\n";
  return out;
}

std::vector<std::string> without_options(const std::vector<std::string>& args,
                                         const std::vector<std::string>& drop) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < args.size(); ++i) {
    bool dropped = false;
    for (const std::string& name : drop) {
      if (args[i] == name) {
        ++i;  // its value
      } else if (!(args[i].rfind(name + "=", 0) == 0 || (name.size() == 2 && args[i].rfind(name, 0) == 0))) {
        continue;
      }
      dropped = true;
      break;
    }
    if (!dropped) out.push_back(args[i]);
  }
  return out;
}

void check_batch_path(const std::string& path, const std::string& option) {
  if (path.find_first_of("\n\r") != std::string::npos)
    throw input_error(option, "a path with a line break cannot be named in a batch script: " + path);
}

fs::path this_program() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw environment_error("/proc/self/exe", "cannot find this program's path: " + ec.message());
  return self;
}

void run_submission(const std::string& mode, const std::string& script, const std::string& program) {
  if (mode == "print") {
    std::fputs(script.c_str(), stdout);
    return;
  }
  std::fflush(stdout);
  FILE* sh = ::popen("/bin/sh -s", "w");
  if (!sh) throw environment_error("/bin/sh", "cannot start the submission");
  const bool written = std::fputs(script.c_str(), sh) >= 0;
  const int status = ::pclose(sh);
  if (!written || status != 0)
    throw environment_error(
        "sbatch", "the submission failed (is Slurm's sbatch on PATH, and SLURM_CONF the cluster's?); " +
                      program + " --slurm print shows what was run");
}

}  // namespace svbrdf
