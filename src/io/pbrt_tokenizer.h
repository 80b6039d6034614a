#pragma once
// The tokens of a pbrt-v3/v4 scene file: directive names, quoted strings, numbers and brackets, each
// with the line it is on; '#' starts a comment to the end of the line.
#include <string>
#include <string_view>

namespace wideray {

struct PbrtToken {
    enum class Kind { Identifier, String, Number, OpenBracket, CloseBracket, End };
    Kind kind = Kind::End;
    std::string text;   ///< the identifier, the string without its quotes, or the number as written
    double number = 0;  ///< Number
    int line = 0;
};

class PbrtTokenizer {
public:
    /// `file` names the text in messages ("FILE:LINE: ...").
    PbrtTokenizer(std::string text, std::string file) : text_(std::move(text)), file_(std::move(file)) {}

    /// The next token (Kind::End at the end). Throws InputError for an unterminated string or a
    /// character that starts no token.
    PbrtToken next();
    const PbrtToken& peek();
    const std::string& file() const { return file_; }
    int line() const { return line_; }

private:
    PbrtToken scan();

    std::string text_, file_;
    size_t pos_ = 0;
    int line_ = 1;
    bool peeked_ = false;
    PbrtToken lookahead_;
};

} // namespace wideray
