#include "commands.hpp"

#include <array>
#include <utility>

namespace bouncer::cli {

CommandSetup command_setup(std::string_view name) {
  static constexpr std::array<std::pair<std::string_view, CommandSetup>, 20> setups{{
      {"orbit", setup_orbit},
      {"certify-sticking", setup_certify_sticking},
      {"certify-periodic", setup_certify_periodic},
      {"certify-chaos", setup_certify_chaos},
      {"check-certificate", setup_check_certificate},
      {"sweep", setup_sweep},
      {"audit", setup_audit},
      {"periodic", setup_periodic},
      {"lyapunov", setup_lyapunov},
      {"classify", setup_classify},
      {"bifurcation", setup_bifurcation},
      {"portrait", setup_portrait},
      {"basin", setup_basin},
      {"attractors", setup_attractors},
      {"scan", setup_scan},
      {"merge", setup_merge},
      {"continue", setup_continue},
      {"trajectory", setup_trajectory},
      {"tongues", setup_tongues},
      {"reproduce", setup_reproduce},
  }};
  for (const auto& [n, setup] : setups)
    if (n == name) return setup;
  return nullptr;
}

}  // namespace bouncer::cli
