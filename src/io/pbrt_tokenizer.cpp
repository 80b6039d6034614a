#include "io/pbrt_tokenizer.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace wideray {

PbrtToken PbrtTokenizer::next() {
    if (peeked_) {
        peeked_ = false;
        return std::move(lookahead_);
    }
    return scan();
}

const PbrtToken& PbrtTokenizer::peek() {
    if (!peeked_) {
        lookahead_ = scan();
        peeked_ = true;
    }
    return lookahead_;
}

PbrtToken PbrtTokenizer::scan() {
    for (;;) {  // white space and comments
        if (pos_ >= text_.size()) return {PbrtToken::Kind::End, "", 0, line_};
        const char c = text_[pos_];
        if (c == '\n') ++line_, ++pos_;
        else if (std::isspace(static_cast<unsigned char>(c))) ++pos_;
        else if (c == '#')
            while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
        else break;
    }
    const char c = text_[pos_];
    const int line = line_;
    if (c == '[' || c == ']') {
        ++pos_;
        return {c == '[' ? PbrtToken::Kind::OpenBracket : PbrtToken::Kind::CloseBracket, std::string(1, c), 0, line};
    }
    if (c == '"') {
        const size_t end = text_.find_first_of("\"\n", pos_ + 1);
        if (end == std::string::npos || text_[end] == '\n')
            throw InputError(file_, "line " + std::to_string(line), "string not closed on its line");
        std::string s = text_.substr(pos_ + 1, end - pos_ - 1);
        pos_ = end + 1;
        return {PbrtToken::Kind::String, std::move(s), 0, line};
    }
    const size_t start = pos_;
    if (std::isalpha(static_cast<unsigned char>(c))) {
        while (pos_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_')) ++pos_;
        return {PbrtToken::Kind::Identifier, text_.substr(start, pos_ - start), 0, line};
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.') {
        while (pos_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '.' ||
                                       text_[pos_] == '-' || text_[pos_] == '+'))
            ++pos_;
        std::string_view s(text_.data() + start, pos_ - start);
        if (s.front() == '+') s.remove_prefix(1);
        double value = 0;
        const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
        if (ec != std::errc() || end != s.data() + s.size())
            throw InputError(file_, "line " + std::to_string(line), "'" + std::string(s) + "' is not a number");
        if (!(std::abs(value) <= double(std::numeric_limits<float>::max())))
            throw InputError(file_, "line " + std::to_string(line), "'" + std::string(s) + "' is not a finite 32-bit float");
        return {PbrtToken::Kind::Number, std::string(s), value, line};
    }
    throw InputError(file_, "line " + std::to_string(line), std::string("unexpected character '") + c + "'");
}

} // namespace wideray
