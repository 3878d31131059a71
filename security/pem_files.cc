#include "security/pem_files.h"

#include <openssl/bio.h>
#include <openssl/err.h>
#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/x509.h>

#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>

#include "absl/strings/match.h"
#include "absl/strings/str_format.h"

namespace afmesh::security {
namespace {

// PEM files are a few KiB; a larger one is not what the flag wants.
constexpr std::size_t kMaxPemBytes = 1 << 20;

struct BioFree {
  void operator()(BIO* bio) const { BIO_free(bio); }
};
struct X509Free {
  void operator()(X509* x509) const { X509_free(x509); }
};
struct KeyFree {
  void operator()(EVP_PKEY* key) const { EVP_PKEY_free(key); }
};
using Bio = std::unique_ptr<BIO, BioFree>;
using Certificate = std::unique_ptr<X509, X509Free>;
using Key = std::unique_ptr<EVP_PKEY, KeyFree>;

// OpenSSL's reason for the last failure on this thread ("" when none), clearing its queue.
std::string openssl_reason() {
  const unsigned long error = ERR_peek_last_error();
  ERR_clear_error();
  if (error == 0) return "";
  const char* reason = ERR_reason_error_string(error);
  return reason == nullptr ? "" : absl::StrFormat(" (%s)", reason);
}

absl::StatusOr<std::string> read_text(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return absl::InvalidArgumentError(absl::StrFormat("%s %s: cannot be read", what, path));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (!in.good() && !in.eof()) {
    return absl::InvalidArgumentError(absl::StrFormat("%s %s: cannot be read", what, path));
  }
  std::string content = std::move(text).str();
  if (content.size() > kMaxPemBytes) {
    return absl::InvalidArgumentError(
        absl::StrFormat("%s %s: %d bytes, more than a PEM file of certificates or a key holds",
                        what, path, content.size()));
  }
  return content;
}

Bio memory_bio(const std::string& text) {
  return Bio(BIO_new_mem_buf(text.data(), static_cast<int>(text.size())));
}

Certificate first_certificate(const std::string& pem) {
  const Bio bio = memory_bio(pem);
  return Certificate(PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr));
}

Key private_key(const std::string& pem) {
  const Bio bio = memory_bio(pem);
  // An empty passphrase callback result: an encrypted key fails instead of prompting.
  return Key(PEM_read_bio_PrivateKey(
      bio.get(), nullptr, [](char*, int, int, void*) { return 0; }, nullptr));
}

}  // namespace

absl::StatusOr<std::string> read_certificates(const std::string& path, const std::string& what) {
  absl::StatusOr<std::string> text = read_text(path, what);
  if (!text.ok()) return text.status();
  if (!absl::StrContains(*text, "-----BEGIN CERTIFICATE-----")) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "%s %s: no PEM certificate in it (expected '-----BEGIN CERTIFICATE-----')", what, path));
  }
  ERR_clear_error();
  const Bio bio = memory_bio(*text);
  int count = 0;
  while (true) {
    const Certificate certificate(PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr));
    if (certificate == nullptr) break;
    ++count;
  }
  // The loop ends at the end of the file (PEM_R_NO_START_LINE) or at a broken certificate.
  const unsigned long error = ERR_peek_last_error();
  const bool at_end =
      ERR_GET_LIB(error) == ERR_LIB_PEM && ERR_GET_REASON(error) == PEM_R_NO_START_LINE;
  if (count == 0 || !at_end) {
    const std::string reason = openssl_reason();
    return absl::InvalidArgumentError(
        absl::StrFormat("%s %s: certificate %d cannot be parsed%s", what, path, count + 1, reason));
  }
  ERR_clear_error();
  return text;
}

absl::StatusOr<std::string> read_private_key(const std::string& path, const std::string& what) {
  absl::StatusOr<std::string> text = read_text(path, what);
  if (!text.ok()) return text.status();
  if (!absl::StrContains(*text, "PRIVATE KEY-----")) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "%s %s: no PEM private key in it (expected '-----BEGIN PRIVATE KEY-----')", what, path));
  }
  if (absl::StrContains(*text, "ENCRYPTED")) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "%s %s: the private key is encrypted; give an unencrypted key (openssl pkey -in KEY -out "
        "PLAIN) and protect the file by its permissions",
        what, path));
  }
  if (private_key(*text) == nullptr) {
    const std::string reason = openssl_reason();
    return absl::InvalidArgumentError(
        absl::StrFormat("%s %s: the private key cannot be parsed%s", what, path, reason));
  }
  return text;
}

absl::Status check_key_matches(const std::string& certificate_pem,
                               const std::string& certificate_path, const std::string& key_pem,
                               const std::string& key_path) {
  const Certificate certificate = first_certificate(certificate_pem);
  const Key key = private_key(key_pem);
  const bool match = certificate != nullptr && key != nullptr &&
                     X509_check_private_key(certificate.get(), key.get()) == 1;
  ERR_clear_error();
  if (match) return absl::OkStatus();
  return absl::InvalidArgumentError(absl::StrFormat(
      "the private key in %s does not belong to the certificate in %s (the first certificate of "
      "the chain must be the one the key signs for)",
      key_path, certificate_path));
}

}  // namespace afmesh::security
