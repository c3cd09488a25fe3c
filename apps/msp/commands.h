#pragma once
// The msp subcommands. Each takes the arguments after its name and returns the exit status;
// errors are thrown (ricci::Error, msp::UsageError) and reported by main().
namespace msp {

int run_info(int argc, char** argv);
int run_generate(int argc, char** argv);
int run_flow(int argc, char** argv);
int run_atlas(int argc, char** argv);
int run_uniformize(int argc, char** argv);
int run_fit(int argc, char** argv);
int run_edit(int argc, char** argv);
int run_eval(int argc, char** argv);
int run_bezier(int argc, char** argv);
int run_module(int argc, char** argv);
int run_index(int argc, char** argv);

}  // namespace msp
