// The source of owsim_module_headers (cmake/owsimModule.cmake), the target that compiles the
// modules' precompiled headers; it holds no code of its own.
