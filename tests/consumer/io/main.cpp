// A consumer of the I/O layer: reads a scene file (argv[1]) and prints the provenance an
// output of that scene would carry. tests/cli/install_consumer.sh checks its first line.
#include <bouncer/io/orbit.hpp>
#include <bouncer/io/provenance.hpp>
#include <bouncer/io/scene.hpp>

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const bouncer::Options o = bouncer::load_scene(argv[1], bouncer::scene_command(argv[1]), bouncer::orbit_keys());
  bouncer::Provenance p;
  p.command = bouncer::scene_command(argv[1]);
  p.inputs = o.inputs();
  p.precision = bouncer::precision_from(o).text();
  std::cout << p.as_comment_lines();
  return bouncer::model_from(o).law == bouncer::Law::constant ? 0 : 1;
}
