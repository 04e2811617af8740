#pragma once
/// @file
/// DDS Security for service sets: the keys and signed documents `roverctl security` makes, and
/// the checks `roverctl up` runs before it starts a secured set (no DDS).
///
/// One certificate authority per security directory (per site: every secured set on the machine
/// shares it) signs an identity per role of core/runtime's topic access table (CN=<role>,
/// O=<site>), the governance document and the permissions document. Governance: unauthenticated
/// participants are refused, discovery and liveliness are encrypted, and every topic's data
/// is encrypted with read and write access control. Permissions: per role one grant that allows
/// publishing exactly the topics it writes and subscribing to those it reads (any partition:
/// the lock-step clock uses per-service partitions), on the set's domains, default DENY.
///
/// Keys are ECDSA P-256 (prime256v1), made by the OpenSSL command-line tool (`openssl`, a
/// Debian package scripts/setup.sh installs); private keys are written with mode 0600 and the
/// directory with 0700. File layout: core/runtime security_files.hpp.

#include <string>
#include <vector>

#include "rover/base/status.hpp"

namespace rover::deploy {

struct SecurityOptions {
  std::string dir;                 ///< the security directory (created 0700)
  std::string site = "rover";      ///< O= of every subject
  int identity_days = 365;         ///< identity certificates' and permissions' validity [days]
  int ca_days = 3650;              ///< the authority's validity [days]
  int domain_min = 0;              ///< domains the governance and grants cover
  int domain_max = 230;  ///< DDS Security documents take domain ids up to 230
  /// Ok, or InvalidArgument naming the field: an empty dir, a site with characters other than
  /// letters, digits, '-', '_', '.' and ' ', non-positive validities, domains outside [0, 230]
  /// or min > max.
  Status Validate() const;
};

/// The security directory of a state root (supervisor.hpp DefaultStateRoot): <root>/security.
std::string SecurityDirOf(const std::string& state_root);

/// Makes the security directory: the authority (kept when it exists, unless `new_authority`),
/// an identity for every role, and the governance and permissions documents, signed. Errors
/// name the step and pass OpenSSL's own message on; a step that fails leaves the files of the
/// previous init in place (new files are written beside and renamed over).
Status InitSecurity(const SecurityOptions& options, bool new_authority);

/// `roverctl security rotate`: new keys and certificates for every role and newly signed
/// documents under the same authority (InitSecurity with new_authority = false, every identity
/// remade).
Status RotateSecurity(const SecurityOptions& options);

/// Checks, for each of `roles` (every role of the table when empty), that its certificate
/// verifies against the authority, is valid now and for at least `margin_days`, and matches its
/// private key; and that the governance and permissions documents verify against the authority
/// and parse. FailedPrecondition naming the first file and what is wrong.
Status VerifySecurity(const std::string& dir, const std::vector<std::string>& roles = {},
                      int margin_days = 0);

/// A human-readable account of the directory: the authority's subject and expiry, per role its
/// certificate's expiry and the topics it may write and read, and each check's result.
Result<std::string> DescribeSecurity(const std::string& dir);

/// The governance and permissions documents, unsigned (exposed for tests and `show`). No XML
/// comments: Cyclone 0.10's parser of these documents refuses them.
std::string GovernanceXml(const SecurityOptions& options);
std::string PermissionsXml(const SecurityOptions& options, const std::string& not_before,
                           const std::string& not_after);

}  // namespace rover::deploy
