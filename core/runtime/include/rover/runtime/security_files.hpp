#pragma once
/// @file
/// Where a set's DDS Security files live and which of them a participant uses (no DDS calls).
///
/// A security directory (made by `roverctl security init`, deploy/security) holds one
/// certificate authority for identities and permissions, the signed governance and permissions
/// documents, and per role (topic_access.hpp) a certificate and its private key:
///
///   <dir>/ca.pem                      the authority's certificate (identity and permissions CA)
///   <dir>/ca.key.pem                  its private key (mode 0600; only roverctl reads it)
///   <dir>/governance.xml, .p7s        what is protected; .p7s is the S/MIME-signed copy used
///   <dir>/permissions.xml, .p7s       one grant per role; signed likewise
///   <dir>/identities/<role>.pem       the role's certificate (subject CN=<role>)
///   <dir>/identities/<role>.key.pem   its private key (mode 0600)
///
/// A process takes part in a secured set when ROVER_SECURITY_DIR names such a directory; its
/// role is ROVER_SECURITY_IDENTITY. dds::Participant::Create then loads Cyclone's three
/// security plugins with these files (DDS Security 1.1 participant properties "dds.sec.*").

#include <optional>
#include <string>

#include "rover/base/status.hpp"

namespace rover::dds {

inline constexpr const char* kSecurityDirVariable = "ROVER_SECURITY_DIR";
inline constexpr const char* kSecurityIdentityVariable = "ROVER_SECURITY_IDENTITY";

struct SecurityFiles {
  std::string ca;           ///< identity CA and permissions CA
  std::string governance;   ///< signed (.p7s)
  std::string permissions;  ///< signed (.p7s)
  std::string certificate;  ///< the role's
  std::string private_key;  ///< the role's
};

/// The files `role` uses in security directory `dir`.
SecurityFiles SecurityFilesFor(const std::string& dir, const std::string& role);

/// Ok when every file exists, is readable and looks like what it should be (a PEM certificate,
/// a PEM private key, an S/MIME signed document); else FailedPrecondition naming the file and
/// what is wrong ("/s/identities/dl-pose.pem: missing: run `roverctl security init`"). Whether
/// a certificate is valid, unexpired and signed by the CA is checked by roverctl (deploy/security)
/// and, at the handshake, by DDS Security itself.
Status CheckSecurityFiles(const SecurityFiles& files);

/// The security directory and role of this process from the environment: nullopt when
/// ROVER_SECURITY_DIR is unset or empty; InvalidArgument when it is set without
/// ROVER_SECURITY_IDENTITY.
struct SecurityIdentity {
  std::string dir;
  std::string role;
};
Result<std::optional<SecurityIdentity>> SecurityIdentityFromEnvironment();

/// The directory holding Cyclone's security plugins (libdds_security_auth.so ...): the
/// ROVER_DDS_SECURITY_LIB_DIR override, else found beside the loaded libddsc (Debian keeps them
/// in its libddsc0debian/ subdirectory). NotFound naming the places looked in.
Result<std::string> SecurityPluginDir();

}  // namespace rover::dds
