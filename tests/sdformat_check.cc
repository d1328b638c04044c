// Parse an SDF file with sdformat and print what it holds: errors, then per model its
// links, joints and plugin file names (one line each). Exit 1 on any error.
#include <iostream>
#include <sdf/sdf.hh>
int main(int argc, char **argv) {
  sdf::Root root;
  sdf::Errors errors = root.Load(argv[1]);
  for (const auto &e : errors) std::cout << "error: " << e << std::endl;
  const sdf::Model *model = root.Model();
  if (!model && root.WorldCount() > 0) model = root.WorldByIndex(0)->ModelByIndex(0);
  if (model) {
    std::cout << "model " << model->Name() << " links " << model->LinkCount()
              << " joints " << model->JointCount() << std::endl;
    for (auto p = model->Element()->GetFirstElement(); p; p = p->GetNextElement())
      if (p->GetName() == "plugin")
        std::cout << "plugin " << p->Get<std::string>("filename") << std::endl;
  }
  return errors.empty() ? 0 : 1;
}
