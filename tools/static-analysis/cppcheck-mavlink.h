/*
 * cppcheck-mavlink.h - forced into every file cppcheck analyses
 * (scripts/static_analysis.sh, --include): the generated MAVLink headers
 * (cmake/mavgen.cmake, <build>/generated) wrap each struct in
 * MAVPACKED(...), whose __attribute__ cppcheck 2.10 cannot parse. For the
 * analysis only the fields matter: the wrapper becomes the declaration
 * itself. The generated headers' own findings are suppressed (they are not
 * our code: docs/static-analysis.md, D-GENERATED).
 */
#ifndef HT_CPPCHECK_MAVLINK_H
#define HT_CPPCHECK_MAVLINK_H
#define MAVPACKED(declaration) declaration
#endif
