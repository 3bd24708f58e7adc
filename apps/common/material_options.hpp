#pragma once
// --material NAME|CSV and --list-materials (bed/material_file.hpp): one material file fills the
// options of every program that needs material data (the list: bed/material_fills.hpp, which the
// Python module's material="NAME" reads too), so a powder's numbers are typed once. An option
// given beside --material wins over the file's value: on the command line always, in the scene
// file when --material is in the scene file too (a scene's 316L values give way to --material
// copper typed at the command line).
#include <boost/program_options.hpp>
#include <set>
#include <string>
#include <vector>

namespace powderbed::app {

// Adds --material and --list-materials; the help names the options of `app` the file fills.
void add_material_options(boost::program_options::options_description& desc, const char* app);

// --list-materials: prints the shipped materials (name and description; --json: one object) and
// returns true. Returns false when it was not asked for.
bool list_materials(const boost::program_options::variables_map& vm);

// The file a material name or path stands for (bed::material_path): a name is the shipped file;
// a relative path is tried from the working folder, then from the --config scene file's folder.
// `option` names the option in messages.
std::string material_file(const std::string& name_or_path,
                          const boost::program_options::variables_map& vm,
                          const std::string& option);

// With --material: reads the file and stores its values into the options of `app` that were not
// given beside it (`typed`: the options the command line gave); returns the options it stored,
// whose values the caller passes on to the fields those options are bound to (parse_options
// does). Throws InputError for an unknown name or a bad file.
std::vector<std::string> apply_material(const char* app, boost::program_options::variables_map& vm,
                                        const std::set<std::string>& typed);

}  // namespace powderbed::app
