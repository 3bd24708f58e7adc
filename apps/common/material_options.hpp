#pragma once
// --material NAME|CSV and --list-materials (bed/material_file.hpp): one material file fills the
// options of every program that needs material data (the list is in material_options.cpp), so a
// powder's numbers are typed once. An option given on the command line or in the scene file wins
// over the file's value.
#include <boost/program_options.hpp>

namespace powderbed::app {

// Adds --material and --list-materials; the help names the options of `app` the file fills.
void add_material_options(boost::program_options::options_description& desc, const char* app);

// --list-materials: prints the shipped materials (name and description; --json: one object) and
// returns true. Returns false when it was not asked for.
bool list_materials(const boost::program_options::variables_map& vm);

// With --material: reads the file and stores its values into the options of `app` that were left
// at their defaults. Throws InputError for an unknown name or a bad file.
void apply_material(const char* app, boost::program_options::variables_map& vm);

}  // namespace powderbed::app
