# Each domain's model: the value types its files hold and their names, which the formats floor reads
# into and writes from. A domain that has one compiles it as a library of its own,
# vstcal_<domain>_model, under the domain's algorithms (vstcal_<domain> links it), so the formats
# floor's readers — and the CI's sanitizer pass, which builds only them (tests/fuzz) — link a
# domain's model without compiling its solvers and detectors. Listed here once for
# lib/CMakeLists.txt and cmake/CheckLayers.cmake, which fails the build when a model file includes
# anything but the foundations and its own domain's model. Entries are stems under lib/vstcal/
# (capture/target: target.h and target.cc); any other file of the folder is the domain's algorithms.
# Domains not listed are one library each: the formats floor links stereo, errsim and report whole
# (their files' writers rectify, evaluate the chain, summarise) and calib not at all.
set(vstcal_domain_models capture handeye)
set(vstcal_model_capture capture/pattern capture/target)
set(vstcal_model_handeye handeye/covariance_names)
