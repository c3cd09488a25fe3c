#include "msp/commands.h"

#include <algorithm>

namespace msp {

const std::vector<Subcommand>& subcommands() {
  static const std::vector<Subcommand> list = {
      {info_command, run_info},
      {generate_command, run_generate},
      {flow_command, run_flow},
      {atlas_command, run_atlas},
      {uniformize_command, run_uniformize},
      {fit_command, run_fit},
      {edit_command, run_edit},
      {eval_command, run_eval},
      {bezier_command, run_bezier},
      {tessellate_command, run_tessellate},
      {module_command, run_module},
      {index_command, run_index},
      {match_command, run_match},
  };
  return list;
}

std::string overview_text() {
  std::size_t width = 0;
  for (const auto& c : subcommands()) width = std::max(width, c.spec().name.size());
  std::string text = "usage: msp <command> [options]\n\ncommands:\n";
  for (const auto& c : subcommands()) {
    const CommandSpec& spec = c.spec();
    text += "  " + spec.name + std::string(width + 2 - spec.name.size(), ' ') + spec.summary + "\n";
  }
  text += "\n`msp <command> --help` describes a command and its options.\n";
  return text;
}

}  // namespace msp
