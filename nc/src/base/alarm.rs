//! The error codes of dialect.md §8, each with a name to search for and
//! the condition the dialect gives it. The codes are a contract: the
//! diagnostics print `E4001`, the canon `ALARM CODE=4001`.

macro_rules! alarms {
    ($($(#[$doc:meta])* $name:ident = $code:literal, $label:literal;)*) => {
        /// An alarm of dialect.md §8.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        #[repr(u16)]
        pub enum Alarm {
            $($(#[$doc])* $name = $code,)*
        }

        impl Alarm {
            /// Every alarm, in the order of dialect.md §8.
            pub const ALL: &'static [Alarm] = &[$(Alarm::$name,)*];

            /// `E4001` as the diagnostics print it.
            pub const fn name(self) -> &'static str {
                match self {
                    $(Alarm::$name => concat!("E", stringify!($code)),)*
                }
            }

            /// The condition of dialect.md §8, in short.
            pub const fn label(self) -> &'static str {
                match self {
                    $(Alarm::$name => $label,)*
                }
            }
        }
    };
}

alarms! {
    // §8.1 Lexical and syntax (compile time).
    BadCharacter = 1001, "character not allowed outside a comment";
    BadComment = 1002, "comment nested, not opened or not closed on its line";
    TextAfterPercent = 1003, "text after % on a % line";
    BadProgramNumber = 1004, "malformed O line or program number";
    ProgramTwice = 1005, "program number defined twice in one file";
    BadSequenceNumber = 1006, "malformed or misplaced N word";
    BadNumber = 1007, "malformed number or word without value";
    UnknownAddress = 1008, "unknown address, letter pair or keyword";
    DecimalPointNotAllowed = 1009, "decimal point on an integer-only address";
    LiteralOutOfRange = 1010, "literal out of range for its address";
    AddressRepeated = 1011, "address or argument repeated in a block";
    TooManyMCodes = 1012, "M codes that cannot stand together";
    MixedBlock = 1013, "NC words and a macro statement in one block";
    ExpressionSyntax = 1014, "expression syntax";
    MisplacedSlash = 1015, "/ not at the start of a block";
    // §8.2 Structure and meaning.
    UnknownGCode = 2001, "unknown G code";
    OneShotConflict = 2002, "group-00 codes or G65/G66 that cannot stand together";
    MissingEquipment = 2003, "code needs equipment the machine lacks";
    ForeignDialect = 2004, "syntax of another dialect";
    AxisNotConfigured = 2005, "axis word for an axis that is not configured";
    MissingWord = 2006, "required word missing";
    IncompatibleWords = 2007, "words that cannot stand together";
    MissingJumpTarget = 2010, "GOTO to a sequence number that does not exist";
    MissingProgram = 2012, "called program found neither in the file nor in a library";
    BadLoopLabel = 2013, "DO/END label other than 1, 2, 3";
    UnbalancedLoop = 2014, "DO and END do not match";
    JumpIntoLoop = 2015, "GOTO from outside into a loop";
    BadProfile = 2020, "G70–G73 profile or its P/Q";
    BadProfileStart = 2021, "G71/G72 ns block";
    ProfileNumberRepeated = 2022, "sequence number of a profile repeated";
    BadCornerLength = 2040, "L with D, L/D on G00, L/D not positive";
    UnknownParameter = 2050, "G10 L52: unknown parameter number";
    BadMacroFunction = 2060, "G65 H: undefined H code or P not a # reference";
    BadMacroArgument = 2061, "G65/G66 argument not allowed";
    NotSupportedYet = 2099, "valid code not supported yet";
    // §8.3 Geometry and machine state.
    ArcRadiusTooSmall = 4001, "half the chord exceeds |R|";
    ArcEndOffCircle = 4002, "arc end point off the circle";
    ThreePointArc = 4004, "G05: points collinear or end = start";
    BadEllipse = 4005, "G6.2/G6.3: A or B missing, or the chord longer than 2A";
    BadParabola = 4006, "G7.2/G7.3: P missing, or the chord parallel to the axis";
    CornerTooLarge = 4007, "chamfer or rounding too large to join the two elements";
    BadAngle = 4008, "angle programming";
    BadRoughing = 4009, "G71/G72/G73 cycle words or profile";
    BadThread = 4010, "thread words out of range";
    ZeroStep = 4011, "G74/G75 zero step between columns or rows";
    PlaneInComp = 4030, "plane changed while compensating";
    CompOnArc = 4031, "compensation started or cancelled on an arc, G31/G53 in it";
    MeasureInComp = 4032, "G36/G37 while compensating or without tool or offset";
    PolarInComp = 4033, "G12.1 while compensating or in G99";
    CompWithoutMoves = 4034, "seven blocks without a move while compensating";
    CallInComp = 4035, "M98 while compensating";
    CompInterference = 4036, "compensation interference";
    // §8.4 Run-time alarms.
    DivisionByZero = 5001, "division by zero";
    NegativeRoot = 5002, "square root of a negative value";
    ArcFunctionRange = 5003, "ASIN/ACOS argument outside -1…1";
    LogOfNonPositive = 5004, "LN of a value ≤ 0";
    UndefinedFunction = 5005, "TAN of 90°, ATAN[0]/[0]";
    NotFinite = 5006, "result not finite";
    VariableAccess = 5007, "variable not readable or not writable";
    NoSuchVariable = 5008, "variable number names no variable";
    NullValue = 5009, "null where a number is needed";
    ValueOutOfRange = 5010, "computed value out of range for its address";
    NegativeBcd = 5011, "BIN/BCD of a negative value";
    JumpTargetMissing = 6001, "jump target missing";
    ReturnTargetMissing = 6002, "M99 P target missing in the calling program";
    CalledProgramMissing = 6003, "called program missing";
    CallsTooDeep = 6004, "call nesting too deep";
    BlockBudget = 6005, "block budget used up";
    ComputedJumpIntoLoop = 6008, "computed GOTO into a loop";
    ZeroFeed = 7001, "feed move with F = 0";
    StrokeLimit = 7002, "stroke limit";
    SpindleStopped = 7003, "per-revolution feed with the spindle stopped";
    ToolNumber = 7004, "tool or offset number above the machine's count";
    ToolLifeOut = 7005, "tool-life group empty or worn out";
    NoMeasuringSignal = 7006, "measuring signal not received";
    NoRepairPosition = 7007, "thread repair: no recorded position";
    UnknownParameterAtRun = 7008, "G10 L52: unknown parameter";
}

impl Alarm {
    /// The number: `E4001` → 4001.
    pub const fn code(self) -> u16 {
        self as u16
    }

    /// The alarm of a number, `None` for one §8 does not list.
    pub fn from_code(code: u16) -> Option<Alarm> {
        Alarm::ALL.iter().copied().find(|a| a.code() == code)
    }

    /// A value outside its address's range, by the word's `flags`: a
    /// written one is the literal's fault (E1010, which the compiler reports
    /// for a static block), a computed one the computation's (E5010).
    pub const fn out_of_range(flags: u8) -> Alarm {
        if flags & crate::base::words::LITERAL != 0 {
            Alarm::LiteralOutOfRange
        } else {
            Alarm::ValueOutOfRange
        }
    }
}

/// The canon's code of an alarm (`ALARM CODE=7002`), as the runtime keeps
/// it beside the numbers programs raise themselves.
impl From<Alarm> for u32 {
    fn from(a: Alarm) -> u32 {
        a.code() as u32
    }
}

#[cfg(test)]
mod tests {
    use super::Alarm;

    #[test]
    fn names_are_the_numbers() {
        // Each name is "E" and the four digits of its number.
        for &a in Alarm::ALL {
            assert_eq!(a.name(), alloc::format!("E{:04}", a.code()));
            assert_eq!(Alarm::from_code(a.code()), Some(a));
            assert!(!a.label().is_empty());
        }
        assert_eq!(Alarm::ArcRadiusTooSmall.name(), "E4001");
        assert_eq!(Alarm::from_code(4003), None);
    }

    #[test]
    fn every_code_of_the_dialect_is_listed() {
        // Counted by hand in dialect.md §8: 15 lexical, 20 structure,
        // 17 geometry, 11 value, 6 control flow, 8 machine alarms.
        assert_eq!(Alarm::ALL.len(), 15 + 20 + 17 + 11 + 6 + 8);
        let mut codes: alloc::vec::Vec<u16> = Alarm::ALL.iter().map(|a| a.code()).collect();
        codes.sort_unstable();
        codes.dedup();
        assert_eq!(codes.len(), Alarm::ALL.len(), "a number twice");
    }
}
