#pragma once
// The transfer part of the modal bank (docs/bank-format.md "Modal bank", /entries/NNNN/transfer
// and /settings/transfer): io/modal_bank.cpp calls these for every entry and the header.
#include <string>

#include "io/h5.hpp"
#include "model/modal_bank.hpp"

namespace clatter::io {

void write_transfer(File& f, const std::string& group, const model::ModalTransfer& t, std::size_t modes);
// Checks lengths, orders, the coefficient count and finiteness; InputError naming file and dataset.
model::ModalTransfer read_transfer(const File& f, const std::string& group, std::size_t modes);

void write_transfer_header(File& f, const std::string& group, const model::TransferSettings& h);
model::TransferSettings read_transfer_header(const File& f, const std::string& group);

}  // namespace clatter::io
